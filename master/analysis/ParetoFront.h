// The Pareto front of points that each cost something and leave some error: the points no
// other point beats on both (as cheap or cheaper and as accurate or more, better in one).
#pragma once

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace prism {

// front[i] is true when point i is on the front. Points with a NaN cost or error never are.
inline std::vector<bool> paretoFront(const std::vector<double>& cost,
                                     const std::vector<double>& error) {
  std::vector<size_t> order(cost.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return cost[a] != cost[b] ? cost[a] < cost[b] : error[a] < error[b];
  });
  std::vector<bool> front(cost.size(), false);
  double best = INFINITY;
  for (const size_t i : order) {
    if (std::isnan(cost[i]) || std::isnan(error[i])) continue;
    if (error[i] < best) {
      front[i] = true;
      best = error[i];
    }
  }
  return front;
}

}  // namespace prism

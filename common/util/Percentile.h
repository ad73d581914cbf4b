// The p-quantile of some numbers, interpolated linearly between the nearest two (p = 0.5: the
// median); 0 for none. Frame-time statistics of the viewer and its benchmark.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace prism {

inline double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double position = p * static_cast<double>(values.size() - 1);
  const size_t below = static_cast<size_t>(position);
  const size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (position - static_cast<double>(below)) * (values[above] - values[below]);
}

}  // namespace prism

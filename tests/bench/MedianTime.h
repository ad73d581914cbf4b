// The benchmark programs' timer: the median wall time of `runs` calls of f, in milliseconds.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace prism::bench {

template <typename F>
double medianMs(int runs, F&& f) {
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    f();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
  }
  std::nth_element(ms.begin(), ms.begin() + runs / 2, ms.end());
  return ms[runs / 2];
}

}  // namespace prism::bench

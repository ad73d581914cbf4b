// Elapsed wall time, for run summaries and bounded waits.
#pragma once

#include <chrono>

namespace prism {

using SteadyClock = std::chrono::steady_clock;

inline double secondsSince(SteadyClock::time_point start) {
  return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

}  // namespace prism

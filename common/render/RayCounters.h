// Rays traced, by kind; summed per tile, per rank and per run.
#pragma once

#include <cstdint>

namespace prism {

struct RayCounters {
  uint64_t primary = 0;
  uint64_t shadow = 0;
  uint64_t secondary = 0;  // reflection and refraction

  uint64_t total() const { return primary + shadow + secondary; }
  RayCounters& operator+=(const RayCounters& o) {
    primary += o.primary;
    shadow += o.shadow;
    secondary += o.secondary;
    return *this;
  }
};

}  // namespace prism

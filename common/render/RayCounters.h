// Rays traced, by kind, and the numbers that went wrong on the way; summed per tile, per rank and
// per run.
#pragma once

#include <cstdint>

namespace prism {

struct RayCounters {
  uint64_t primary = 0;
  uint64_t shadow = 0;
  uint64_t secondary = 0;  // reflection and refraction
  // Samples that came out NaN or infinite (an extreme light, a light on a surface, degenerate
  // geometry), and pixels whose finite samples summed past the float range: each is black in
  // the image instead, so no NaN or infinity reaches a pixel. Not rays; counted alongside them.
  uint64_t nonFinite = 0;

  uint64_t total() const { return primary + shadow + secondary; }
  RayCounters& operator+=(const RayCounters& o) {
    primary += o.primary;
    shadow += o.shadow;
    secondary += o.secondary;
    nonFinite += o.nonFinite;
    return *this;
  }
  // What was counted since `o`, an earlier reading of the same counters.
  RayCounters& operator-=(const RayCounters& o) {
    primary -= o.primary;
    shadow -= o.shadow;
    secondary -= o.secondary;
    nonFinite -= o.nonFinite;
    return *this;
  }
};

}  // namespace prism

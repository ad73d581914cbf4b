// A ray with its valid parameter interval [tMin, tMax].
#pragma once

#include <limits>

#include "math/Vec.h"

namespace prism {

struct Ray {
  Vec3 origin{0.0f};
  Vec3 direction{0.0f, 0.0f, 1.0f};  // not necessarily unit length for every caller; see users
  float tMin = 0.0f;
  float tMax = std::numeric_limits<float>::infinity();

  Vec3 at(float t) const { return origin + t * direction; }
};

}  // namespace prism

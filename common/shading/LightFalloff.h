// A point light's distance falloff 1 / (a + b·d + c·d²), and the same relative to
// inverse-square. Direct light uses the first; photons and caustic-map texels, whose density
// already falls as 1/d², carry the second so caustics agree with direct light for any falloff.
#pragma once

#include "scene/SceneDescription.h"

namespace prism {

inline float attenuationFactor(const Attenuation& a, float distance) {
  return 1.0f / (a.constant + a.linear * distance + a.quadratic * distance * distance);
}

// attenuationFactor(a, d) · d²: exactly 1 for the physical (0, 0, 1).
inline float falloffRelativeToInverseSquare(const Attenuation& a, float distance) {
  return 1.0f / (a.constant / (distance * distance) + a.linear / distance + a.quadratic);
}

}  // namespace prism

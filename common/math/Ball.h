// A ball that holds a primitive: how the photon emitter aims at a caustic caster.
#pragma once

#include "math/Aabb.h"

namespace prism {

struct Ball {
  Vec3 center{0.0f};
  float radius = 0.0f;
};

// The ball through the box's corners.
inline Ball ballAround(const Aabb& box) {
  return {box.center(), 0.5f * glm::length(box.extent())};
}

}  // namespace prism

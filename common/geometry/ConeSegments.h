// How a cone enters the BVH: a long slanted cone's box is mostly empty space, so rays that pass
// nowhere near it still test it. Cut along its axis, its parts' boxes hug it.
#pragma once

#include <vector>

#include "geometry/Cone.h"

namespace prism {

// The parts (Cone::segment) a cone enters the BVH as: one, the cone itself, unless cutting it
// shrinks the boxes' total surface area (what the SAH charges a ray for) enough to pay for the
// extra entries.
std::vector<Cone> bvhParts(const Cone& cone);

// How many parts bvhParts makes, without making them (the memory estimate counts them).
int bvhPartCount(const Cone& cone);

}  // namespace prism

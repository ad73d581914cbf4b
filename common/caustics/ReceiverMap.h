// The receiver position map of caustic mapping: per light-space texel, the first surface that
// receives caustics along the light's ray, with casters left out (as if only receivers were
// rendered from the light). The iteration that finds where a refracted ray lands reads it, and
// the lookup uses it as a shadow map: a shading point gets the caustic of a texel only when it
// is the receiver that texel sees.
#pragma once

#include <cstdint>
#include <vector>

#include "caustics/LightFrustum.h"
#include "scene/Scene.h"
#include "util/HugePages.h"

namespace prism {

struct ReceiverTexel {
  Vec3 position{0.0f};
  Vec3 normal{0.0f};      // unit, facing the light
  float distance = 0.0f;  // from the light
  float cosine = 0.0f;    // between the normal and the direction to the light
  bool valid = false;     // false: nothing, or an object with caustics off, in the way
};

class ReceiverMap {
 public:
  // Renders the receivers of every view of `frustum` with `threads` threads (0: all cores).
  ReceiverMap(const Scene& scene, const LightFrustum& frustum, int threads);

  int resolution() const { return n_; }
  const ReceiverTexel& at(int view, int i, int j) const {
    return texels_[(static_cast<size_t>(view) * n_ + j) * n_ + i];
  }
  // The texel containing continuous coordinates (x, y).
  const ReceiverTexel& nearest(const LightSpacePoint& p) const;
  size_t validCount() const;

 private:
  int n_ = 0;
  HugePageVector<ReceiverTexel> texels_;  // view-major, then rows
};

}  // namespace prism

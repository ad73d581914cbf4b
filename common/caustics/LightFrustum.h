// The light-space grid of caustic mapping (Shah et al. 2007): square perspective views from a
// point light, each an N×N texel grid on the plane at distance 1 along the view's axis.
//   One view when the casters fit in a cone of half-angle ≤ 75° (150° across) around their
//   mean direction: all N² texels look at the casters, as in the thesis's spot-light frustum.
//   Six cube faces (90° each) otherwise — the light inside a caster's bounds, casters all
//   around the light, or an infinite casting plane — so no direction towards a caster is lost.
// Receivers and caustics outside the views are not represented (docs/caustics.md).
#pragma once

#include <optional>
#include <vector>

#include "math/Simd.h"
#include "math/Vec.h"
#include "scene/Scene.h"

namespace prism {

struct LightView {
  Vec3 axis{0.0f, 0.0f, 1.0f}, right{1.0f, 0.0f, 0.0f}, up{0.0f, 1.0f, 0.0f};  // orthonormal
  float tanHalf = 1.0f;  // half the side of the grid on the plane at distance 1
};

// A point in light space: view, continuous texel coordinates (texel centres at i + 0.5) and
// the distance from the light.
struct LightSpacePoint {
  int view = 0;
  float x = 0.0f, y = 0.0f;
  float distance = 0.0f;
};

class LightFrustum {
 public:
  // A frustum over the casters as seen from `light`; empty when there are none.
  LightFrustum(const Vec3& light, const std::vector<CasterBounds>& casters, int resolution);

  bool empty() const { return views_.empty(); }
  bool cube() const { return views_.size() == 6; }
  int resolution() const { return n_; }
  const Vec3& light() const { return light_; }
  const std::vector<LightView>& views() const { return views_; }
  // Half-angle of the single view's cone, degrees (45 per cube face).
  float halfAngleDegrees() const;

  // Unit direction from the light through texel coordinates (x, y) of a view.
  Vec3 direction(int view, float x, float y) const;
  // Solid angle of texel (i, j) of any view, sr.
  double texelSolidAngle(int i, int j) const;
  // Where `p` lies in light space; none when it is behind or outside every view.
  std::optional<LightSpacePoint> project(const Vec3& p) const;

 private:
  // A view's axis, right and up as the lanes of three columns, so project() takes the three
  // dot products with a point at once, and its texels per unit of the plane at distance 1.
  struct ViewColumns {
    simd::Float4 x, y, z;  // lanes: axis, right, up, 0
    float scale = 1.0f;    // n / (2 tanHalf)
  };

  Vec3 light_;
  int n_ = 0;
  std::vector<LightView> views_;
  std::vector<ViewColumns> columns_;  // one per view
};

}  // namespace prism

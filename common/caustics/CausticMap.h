// The caustic map of one point light (Shah, Konttinen & Pattanaik 2007), built on the CPU:
//   1. receiver position map (ReceiverMap) and caster maps (first caster surface per texel);
//   2. per caster texel, the light is reflected and refracted with the Fresnel split of eye rays
//      and photons (SpecularSplit); where each leaving ray meets the receivers is estimated by the
//      thesis's iteration on the receiver map (d = 1; P' = P + d·dir; read the receiver R at
//      P''s texel; d = |R − P|; repeat), and the texel's flux, I·Ω_texel·weight, is splatted
//      bilinearly into the receiver texels around the estimate;
//   3. flux per receiver texel becomes irradiance, E = Φ / (Ω_texel·d²/cos θ), in W/m² like the
//      photon map's estimate; a separable Gaussian smooths it.
// Every texel depends only on the scene, and splats are added in texel order, so the map is
// bit-identical for any thread or rank count.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "caustics/LightFrustum.h"
#include "caustics/ReceiverMap.h"
#include "math/Aabb.h"
#include "scene/Scene.h"
#include "util/HugePages.h"

namespace prism {

struct CasterTexel {
  Vec3 position{0.0f};
  Vec3 normal{0.0f};  // shading normal, facing the light
  bool valid = false;
};

struct CausticMapStats {
  int views = 0;
  size_t receiverTexels = 0;  // texels with a receiver
  size_t casterTexels = 0;    // texels whose first surface casts
  size_t paths = 0;           // rays that left the casters towards receivers
  size_t splatted = 0;        // of those, estimates that landed on a receiver texel
  size_t lost = 0;            // estimates that left the map or met no receiver
  double emittedFlux = 0.0;   // mean over channels, W, through caster texels
  double splattedFlux = 0.0;  // mean over channels, W
  double receiverSeconds = 0.0, casterSeconds = 0.0, filterSeconds = 0.0;
  CausticMapStats& operator+=(const CausticMapStats& o);
};

class CausticMap {
 public:
  CausticMap(const Scene& scene, size_t lightIndex, const CausticSettings& settings, int threads);

  bool empty() const { return frustum_.empty(); }
  const LightFrustum& frustum() const { return frustum_; }
  const ReceiverMap& receivers() const { return *receivers_; }
  const HugePageVector<CasterTexel>& casters() const { return casters_; }
  // Caustic irradiance of a receiver texel (W/m²), numbered view-major then rows, after the blur.
  const Color& texelIrradiance(size_t texel) const { return lookup_[texel].irradiance; }
  size_t texelCount() const { return lookup_.size(); }
  const CausticMapStats& stats() const { return stats_; }

  // Caustic irradiance at a receiver point facing `normal`: bilinear over the texels around its
  // projection whose receiver is this point (within a depth tolerance) and faces its way.
  Color irradiance(const Vec3& position, const Vec3& normal) const;
  // sums[i] += irradiance(points[i]->position, points[i]->geometricNormal) for `count` points:
  // every point projected and its texels found first, then the texels read, so that the reads,
  // which mostly miss the cache, overlap instead of waiting one by one.
  void addIrradiance(const SurfaceHit* const* points, int count, Color* sums) const;
  // Bytes a texel's lookup record takes (beside the receiver and caster texels).
  static constexpr size_t kLookupTexelBytes = 32;

  // How far a point's distance from the light may differ from a texel's receiver and still be
  // that receiver: a texel's footprint along the surface's slope, plus a little for float error.
  // texelSize: a texel's width on the plane at distance 1.
  static float depthTolerance(const ReceiverTexel& t, float texelSize);
  // Holds every point irradiance() can give a non-zero answer: lookups outside return at once.
  const Aabb& litBounds() const { return lit_; }

 private:
  LightFrustum frustum_;
  std::unique_ptr<ReceiverMap> receivers_;
  HugePageVector<CasterTexel> casters_;
  // What a lookup reads of a texel, in one 32-byte record: two share a cache line, where the
  // receiver map's texel and the irradiance apart took up to two lines each. blend() reads its
  // halves as vectors of four: (normal, distance) and (tolerance, irradiance).
  struct alignas(32) LookupTexel {
    Vec3 normal{0.0f};  // the receiver's; zero where there is none, which fails every lookup
    float distance = 0.0f;
    float tolerance = 0.0f;  // depthTolerance() of the receiver
    Color irradiance{0.0f};
  };
  static_assert(sizeof(LookupTexel) == kLookupTexelBytes);
  static_assert(offsetof(LookupTexel, distance) == 12 && offsetof(LookupTexel, tolerance) == 16 &&
                offsetof(LookupTexel, irradiance) == 20);

  // Where a point reads the map: its four texels (corner c at (i0 + (c & 1), j0 + (c >> 1)),
  // clamped to the grid), its bilinear weights and its distance from the light.
  struct TexelCorners {
    const LookupTexel* corners[4];
    float ax, ay, distance;
  };
  // False where the point can read nothing (outside the lit box, behind or beside every view).
  bool locate(const Vec3& position, TexelCorners& at) const;
  // The bilinear blend of the corners that pass the shadow-map test for a point facing `normal`.
  static Color blend(const TexelCorners& at, const Vec3& normal);

  HugePageVector<LookupTexel> lookup_;
  Aabb lit_;
  CausticMapStats stats_;
};

}  // namespace prism

// The one question the eye-ray integrator asks a caustics method: how much caustic irradiance
// arrives at this point of a receiving surface. Photon mapping answers it now; caustic mapping
// answers it behind the same interface, so either can be switched in.
#pragma once

#include "geometry/HitRecord.h"
#include "math/RayDifferential.h"
#include "math/Vec.h"

namespace prism {

class CausticEstimator {
 public:
  virtual ~CausticEstimator() = default;
  // Irradiance in W/m² per channel arriving at position on the side normal faces (unit normal).
  virtual Color irradiance(const Vec3& position, const Vec3& normal) const = 0;
  // The same at a surface point the renderer computed: estimators that trace rays from the point
  // start them s.leavingDistance off the surface (math/RayOffset.h). footprint is the pixel's
  // area around the point (math/RayDifferential.h), when known: estimators that average over an
  // area give the average over it, the others ignore it.
  virtual Color irradianceAt(const SurfaceHit& s, const PixelFootprint& footprint = {}) const {
    (void)footprint;
    return irradiance(s.position, s.geometricNormal);
  }
  // irradianceAt(*points[i]) for each of `count` points (no footprint: a packet's points), into
  // out[i]. Estimators whose lookups wait on memory override it to overlap the points' reads;
  // each answer is the one irradianceAt gives, to the bit.
  virtual void irradianceAtEach(const SurfaceHit* const* points, int count, Color* out) const {
    for (int i = 0; i < count; ++i) out[i] = irradianceAt(*points[i]);
  }
  // Whether irradianceAt reads the footprint. The renderer carries ray differentials only for
  // estimators that do: they cost every ray of a frame some arithmetic.
  virtual bool usesFootprint() const { return false; }
};

}  // namespace prism

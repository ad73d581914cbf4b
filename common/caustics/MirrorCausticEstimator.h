// Exact caustic irradiance for scenes whose caustic casters are flat mirrors in one plane: the
// analytic reference of `prism sweep`. Light a flat mirror reflects onto a receiver comes from
// the light's mirror image behind it, so at a receiver point p the caustic irradiance is
//   E(p) = Σ R · I · f(|L − m|) · cos θ / |p − L'|²
// over the lights L and mirror facets whose reflection point m (where the segment from the
// image L' to p crosses the facet) lies inside the facet, with L → m and m → p unblocked; f is
// the light's falloff relative to inverse square (as photons carry it), θ the angle at p.
// The casters must all lie in one plane, so no light reaches a receiver by two mirrors.
#pragma once

#include <string>
#include <vector>

#include "caustics/CausticEstimator.h"
#include "scene/Scene.h"

namespace prism {

class MirrorCausticEstimator : public CausticEstimator {
 public:
  // Throws std::invalid_argument saying why the scene has no such closed form: a caster that is
  // curved, smooth-shaded, refracting or not a mirror, or casters in more than one plane. The
  // scene must outlive the estimator (shadow rays go through it).
  MirrorCausticEstimator(const SceneDescription& description, const Scene& scene);

  // position is taken as exact (a point given, not computed).
  Color irradiance(const Vec3& position, const Vec3& normal) const override;
  // Exact at the point: the footprint is not used.
  Color irradianceAt(const SurfaceHit& s, const PixelFootprint& footprint = {}) const override;

  size_t facetCount() const { return facets_.size(); }

 private:
  struct Facet {
    Vec3 v0, e1, e2;  // a triangle; unused for a plane
    bool unbounded;   // an infinite plane
    Vec3 normal;      // unit
    float offset;     // dot(normal, x) on the facet's plane
    Color reflectance;
  };

  // leaving: how far rays from position start off the surface (SurfaceHit::leavingDistance).
  Color irradianceWithin(const Vec3& position, const Vec3& normal, float leaving) const;
  bool insideFacet(const Facet& facet, const Vec3& point) const;
  // Whether nothing lies between origin and a point on a mirror.
  bool unblocked(const Vec3& origin, const Vec3& mirrorPoint) const;

  const Scene& scene_;
  std::vector<Facet> facets_;
  std::vector<PointLightDesc> lights_;
};

}  // namespace prism

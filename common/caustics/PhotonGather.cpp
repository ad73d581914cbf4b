#include "caustics/PhotonGather.h"

#include <cmath>

#include "caustics/DensityKernel.h"
#include "util/Parallel.h"

namespace prism {

std::vector<float> photonRadii(const PhotonMap& map, int k, float maxRadius, int threads) {
  std::vector<float> radii(map.size());
  const float maxRadius2 = maxRadius * maxRadius;
  const std::vector<uint32_t> order = map.spatialOrder();
  parallelFor(order.size(), threads, [&](uint64_t n) {
    thread_local std::vector<PhotonNeighbour> neighbours;
    const uint32_t i = order[n];
    radii[i] = std::sqrt(map.nearest(map.photons()[i].position, k, maxRadius2, neighbours));
  });
  return radii;
}

PhotonGather::PhotonGather(std::shared_ptr<const PhotonMap> map,
                           const PhotonGatherSettings& settings, int threads)
    : map_(std::move(map)), settings_(settings) {
  if (settings_.fixedRadius || map_->size() == 0) return;
  std::vector<float> radii = photonRadii(*map_, settings_.k, settings_.radius, threads);
  for (float& r : radii) r *= settings_.radiusScale;
  discs_ = std::make_unique<const PhotonDiscs>(map_->photons(), radii);
}

Color PhotonGather::irradiance(const Vec3& position, const Vec3& normal) const {
  return irradianceWithin(position, normal, {});
}

Color PhotonGather::irradianceAt(const SurfaceHit& s, const PixelFootprint& footprint) const {
  return irradianceWithin(s.position, s.geometricNormal, footprint);
}

Color PhotonGather::irradianceWithin(const Vec3& position, const Vec3& normal,
                                     const PixelFootprint& footprint) const {
  const std::vector<Photon>& photons = map_->photons();
  // A photon whose kernel covers less than the footprint's area counts in the footprint.
  const float reach = footprint.valid ? footprint.reach() : 0.0f;
  const float area = footprint.valid ? footprint.area() : 0.0f;
  const float narrow2 = area * kInvPi;  // the squared radius of a disc of that area
  const PixelFootprint::Test inFootprint =
      footprint.valid ? footprint.test(normal) : PixelFootprint::Test{};
  Color sum(0.0f);
  if (!settings_.fixedRadius) {
    if (!discs_) return sum;
    // Photons wider than the footprint through their kernel, narrower ones through the
    // footprint (without one, narrow2 is 0 and every photon is wide).
    discs_->covering(position, [&](uint32_t index, float distance2, float radius2) {
      if (radius2 <= narrow2) return;
      const Photon& p = photons[index];
      if (glm::dot(p.directionVector(), normal) >= 0.0f) return;  // arrived from behind
      sum += p.power * densityKernel(settings_.filter, distance2, radius2);
    });
    if (footprint.valid) {
      discs_->narrowWithin(position, reach, narrow2, [&](uint32_t index, float, float) {
        const Photon& p = photons[index];
        if (glm::dot(p.directionVector(), normal) >= 0.0f) return;  // arrived from behind
        if (inFootprint.contains(p.position - position)) sum += p.power / area;
      });
    }
    return sum;
  }
  thread_local std::vector<PhotonNeighbour> neighbours;
  const float radius2 = settings_.radius * settings_.radius;
  const bool narrow = radius2 <= narrow2;
  map_->within(position, narrow ? reach * reach : radius2, neighbours);
  for (const PhotonNeighbour& n : neighbours) {
    const Photon& p = photons[n.index];
    if (glm::dot(p.directionVector(), normal) >= 0.0f) continue;  // arrived from behind
    if (!narrow) {
      sum += p.power * densityKernel(settings_.filter, n.distance2, radius2);
    } else if (inFootprint.contains(p.position - position)) {
      sum += p.power / area;
    }
  }
  return sum;
}

}  // namespace prism

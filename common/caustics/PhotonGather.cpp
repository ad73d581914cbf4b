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
  const std::vector<Photon>& photons = map_->photons();
  Color sum(0.0f);
  if (!settings_.fixedRadius) {
    if (!discs_) return sum;
    discs_->covering(position, [&](uint32_t index, float distance2, float radius2) {
      const Photon& p = photons[index];
      if (glm::dot(p.directionVector(), normal) >= 0.0f) return;  // arrived from behind
      sum += p.power * densityKernel(settings_.filter, distance2, radius2);
    });
    return sum;
  }
  thread_local std::vector<PhotonNeighbour> neighbours;
  const float radius2 = settings_.radius * settings_.radius;
  map_->within(position, radius2, neighbours);
  for (const PhotonNeighbour& n : neighbours) {
    const Photon& p = photons[n.index];
    if (glm::dot(p.directionVector(), normal) >= 0.0f) continue;  // arrived from behind
    sum += p.power * densityKernel(settings_.filter, n.distance2, radius2);
  }
  return sum;
}

}  // namespace prism

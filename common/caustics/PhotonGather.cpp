#include "caustics/PhotonGather.h"

#include <cmath>

#include "caustics/AutomaticGather.h"
#include "caustics/DensityKernel.h"
#include "util/Parallel.h"

namespace prism {

std::vector<float> photonRadii(const PhotonMap& map, int k, float maxRadius, bool automaticK,
                               int threads) {
  std::vector<float> radii(map.size());
  const float maxRadius2 = maxRadius * maxRadius;
  const std::vector<uint32_t> order = map.spatialOrder();
  parallelFor(order.size(), threads, [&](uint64_t n) {
    thread_local std::vector<PhotonNeighbour> neighbours;
    // The last photon this thread placed, and its radius (negative: fewer than k in reach). Left
    // over from an earlier map or a far chunk, it only makes a loose bound.
    thread_local Vec3 lastPosition(0.0f);
    thread_local float lastRadius = -1.0f;
    const uint32_t i = order[n];
    const Vec3& position = map.photons()[i].position;
    // Photons are placed in spatial order, so the last one is near: its k nearest lie within its
    // radius plus the step from it (a little more, for rounding), and a search bounded there
    // prunes from the start where one bounded by maxRadius first walks until it has k. Finding k
    // below the bound, it has found the k nearest of all, the same photons with the same
    // distances; finding fewer, the full search runs.
    float radius2 = -1.0f;
    if (lastRadius >= 0.0f) {
      const float bound = 1.001f * (glm::length(position - lastPosition) + lastRadius);
      if (bound * bound < maxRadius2) {
        const float found2 = map.nearest(position, k, bound * bound, neighbours);
        if (neighbours.size() == static_cast<size_t>(k)) radius2 = found2;
      }
    }
    if (radius2 < 0.0f) radius2 = map.nearest(position, k, maxRadius2, neighbours);
    lastPosition = position;
    lastRadius = neighbours.size() == static_cast<size_t>(k) ? std::sqrt(radius2) : -1.0f;
    radii[i] = std::sqrt(automaticK ? automaticGatherRadius2(neighbours, k, maxRadius2) : radius2);
  });
  return radii;
}

PhotonGather::PhotonGather(std::shared_ptr<const PhotonMap> map,
                           const PhotonGatherSettings& settings, int threads)
    : map_(std::move(map)), settings_(settings) {
  if (settings_.fixedRadius || map_->size() == 0) return;
  std::vector<float> radii =
      photonRadii(*map_, settings_.k, settings_.radius, settings_.automaticK, threads);
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
  // With a footprint the estimate is the pixel's average of the photons' kernels: a photon
  // narrower than the footprint (a disc of less area) counts its power over the footprint's area
  // if it lies in it; one up to the footprint's reach wide, the mean of its kernel over the
  // footprint; a wider one, its kernel at the centre, as without a footprint. Flipping straight
  // from the first rule to the last left a photon counted in no pixel or in two where pixels'
  // footprints differ (seen through a lens): the glass ball's focus seen from above read 9 %
  // high at k = 400 (docs/accuracy.md).
  const float reach = footprint.valid ? footprint.reach() : 0.0f;
  const float area = footprint.valid ? footprint.area() : 0.0f;
  const float narrow2 = area * kInvPi;
  const float averaged2 = footprint.valid ? std::max(narrow2, reach * reach) : 0.0f;
  const PixelFootprint::Test inFootprint =
      footprint.valid ? footprint.test(normal) : PixelFootprint::Test{};
  // p: a Photon, or a PhotonDiscs::Disc (the same photon, in tree order).
  const auto overFootprint = [&](const auto& p, float radius2) {
    const Vec3 q = p.position - position;
    if (radius2 <= narrow2) return inFootprint.contains(q) ? 1.0f / area : 0.0f;
    return footprintMeanKernel(settings_.filter, q, footprint.a, footprint.b, radius2);
  };
  // Photons that arrived from behind the surface (through a thin wall) are left out.
  const auto fromFront = [&](const auto& p) {
    return glm::dot(p.directionVector(), normal) < 0.0f;
  };
  Color sum(0.0f);
  if (!settings_.fixedRadius) {
    if (!discs_) return sum;
    discs_->covering(position, [&](const PhotonDiscs::Disc& p, float distance2, float radius2) {
      if (radius2 > averaged2 && fromFront(p))
        sum += p.power * densityKernel(settings_.filter, distance2, radius2);
    });
    if (footprint.valid) {
      discs_->reaching(position, reach, averaged2,
                       [&](const PhotonDiscs::Disc& p, float, float radius2) {
                         if (fromFront(p)) sum += p.power * overFootprint(p, radius2);
                       });
    }
    return sum;
  }
  thread_local std::vector<PhotonNeighbour> neighbours;
  const std::vector<Photon>& photons = map_->photons();
  const float radius2 = settings_.radius * settings_.radius;
  const bool averaged = radius2 <= averaged2;
  const float gatherRadius = averaged ? settings_.radius + reach : settings_.radius;
  map_->within(position, gatherRadius * gatherRadius, neighbours);
  for (const PhotonNeighbour& n : neighbours) {
    const Photon& p = photons[n.index];
    if (!fromFront(p)) continue;
    sum += p.power * (averaged ? overFootprint(p, radius2)
                               : densityKernel(settings_.filter, n.distance2, radius2));
  }
  return sum;
}

}  // namespace prism

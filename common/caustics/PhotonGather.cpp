#include "caustics/PhotonGather.h"

#include "caustics/DensityKernel.h"

namespace prism {

Color PhotonGather::irradiance(const Vec3& position, const Vec3& normal) const {
  thread_local std::vector<PhotonNeighbour> neighbours;
  const float maxRadius2 = settings_.radius * settings_.radius;
  float radius2 = maxRadius2;
  if (settings_.fixedRadius) {
    map_->within(position, maxRadius2, neighbours);
  } else {
    radius2 = map_->nearest(position, settings_.k, maxRadius2, neighbours);
  }
  if (neighbours.empty() || !(radius2 > 0.0f)) return Color(0.0f);
  Color sum(0.0f);
  const std::vector<Photon>& photons = map_->photons();
  for (const PhotonNeighbour& n : neighbours) {
    const Photon& p = photons[n.index];
    if (glm::dot(p.directionVector(), normal) >= 0.0f) continue;  // arrived from behind
    sum += p.power * densityKernel(settings_.filter, n.distance2, radius2);
  }
  return sum;
}

}  // namespace prism

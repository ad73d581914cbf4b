#include "caustics/CausticMapEstimator.h"

namespace prism {

CausticMapEstimator::CausticMapEstimator(const Scene& scene, const CausticSettings& settings,
                                         int threads) {
  for (size_t i = 0; i < scene.lights().size(); ++i) {
    auto map = std::make_unique<CausticMap>(scene, i, settings, threads);
    if (!map->empty() && map->stats().casterTexels > 0) maps_.push_back(std::move(map));
  }
}

Color CausticMapEstimator::irradiance(const Vec3& position, const Vec3& normal) const {
  Color sum(0.0f);
  for (const auto& map : maps_) sum += map->irradiance(position, normal);
  return sum;
}

void CausticMapEstimator::irradianceAtEach(const SurfaceHit* const* points, int count,
                                           Color* out) const {
  for (int i = 0; i < count; ++i) out[i] = Color(0.0f);
  for (const auto& map : maps_) map->addIrradiance(points, count, out);
}

CausticMapStats CausticMapEstimator::stats() const {
  CausticMapStats s;
  for (const auto& map : maps_) s += map->stats();
  return s;
}

}  // namespace prism

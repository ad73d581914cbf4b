#include "caustics/ReceiverMap.h"

#include <algorithm>

#include "util/Parallel.h"

namespace prism {

ReceiverMap::ReceiverMap(const Scene& scene, const LightFrustum& frustum, int threads)
    : n_(frustum.resolution()) {
  const int views = static_cast<int>(frustum.views().size());
  texels_.resize(static_cast<size_t>(views) * n_ * n_);
  constexpr int kMaxSkips = 64;  // casters passed through along one ray
  parallelFor(static_cast<uint64_t>(views) * n_, threads, [&](uint64_t r) {
    const int row = static_cast<int>(r);
    const int view = row / n_, j = row % n_;
    for (int i = 0; i < n_; ++i) {
      ReceiverTexel& t = texels_[(static_cast<size_t>(view) * n_ + j) * n_ + i];
      Ray ray{frustum.light(), frustum.direction(view, i + 0.5f, j + 0.5f)};
      for (int skip = 0; skip < kMaxSkips; ++skip) {
        HitRecord hit;
        if (!scene.intersect(ray, hit)) break;
        const SurfaceHit s = scene.surface(ray, hit);
        if (s.caustic & kReceivesCaustics) {
          t.position = s.position;
          t.normal = s.shadingNormal;
          t.distance = glm::length(s.position - frustum.light());
          t.cosine = std::max(0.0f, glm::dot(-ray.direction, s.shadingNormal));
          t.valid = t.cosine > 0.0f;
          break;
        }
        if (!(s.caustic & kCastsCaustics)) break;  // caustics off: it blocks the light
        ray.origin = s.rayOrigin(ray.direction);
      }
    }
  });
}

const ReceiverTexel& ReceiverMap::nearest(const LightSpacePoint& p) const {
  const int i = std::clamp(static_cast<int>(p.x), 0, n_ - 1);
  const int j = std::clamp(static_cast<int>(p.y), 0, n_ - 1);
  return at(p.view, i, j);
}

size_t ReceiverMap::validCount() const {
  return static_cast<size_t>(std::count_if(texels_.begin(), texels_.end(),
                                           [](const ReceiverTexel& t) { return t.valid; }));
}

}  // namespace prism

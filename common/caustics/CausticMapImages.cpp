#include "caustics/CausticMapImages.h"

#include <algorithm>

namespace prism {

std::vector<NamedImage> causticMapImages(const CausticMap& map) {
  const int n = map.frustum().resolution();
  const int views = static_cast<int>(map.frustum().views().size());
  std::vector<NamedImage> out{{"receivers", ImageRgb(n * views, n)},
                              {"casters", ImageRgb(n * views, n)},
                              {"normals", ImageRgb(n * views, n)},
                              {"caustics", ImageRgb(n * views, n)}};
  // Positions are shown relative to the box the receiver and caster texels span.
  Vec3 lo(1e30f), hi(-1e30f);
  std::vector<float> lit;  // the caustic texels' brightness
  for (int v = 0; v < views; ++v) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const size_t k = (static_cast<size_t>(v) * n + j) * n + i;
        const ReceiverTexel& r = map.receivers().at(v, i, j);
        if (r.valid) lo = glm::min(lo, r.position), hi = glm::max(hi, r.position);
        const CasterTexel& c = map.casters()[k];
        if (c.valid) lo = glm::min(lo, c.position), hi = glm::max(hi, c.position);
        const float e = maxComponent(map.texelIrradiance(k));
        if (e > 0.0f) lit.push_back(e);
      }
    }
  }
  const Vec3 span = glm::max(hi - lo, Vec3(1e-6f));
  // Positions map into [1/32, 1] so that only empty texels are black: a texel at the box's
  // lowest corner (exact on a y = 0 floor) would otherwise look empty.
  constexpr float kDarkest = 1.0f / 32.0f;
  const auto shade = [&](const Vec3& p) { return kDarkest + (1.0f - kDarkest) * (p - lo) / span; };
  // White at the 99.5th percentile of the lit texels, not the brightest: a focus a few texels
  // wide would otherwise leave the rest of the caustic too dark to see.
  float white = 0.0f;
  if (!lit.empty()) {
    const size_t at =
        std::min(lit.size() - 1,
                 static_cast<size_t>(kCausticWhitePercentile * static_cast<double>(lit.size())));
    std::nth_element(lit.begin(), lit.begin() + static_cast<std::ptrdiff_t>(at), lit.end());
    white = lit[at];
  }
  for (int v = 0; v < views; ++v) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const size_t k = (static_cast<size_t>(v) * n + j) * n + i;
        // Row j = 0 is the bottom of the light's grid; images run top down.
        const size_t px = static_cast<size_t>(n - 1 - j) * (n * views) + v * n + i;
        const ReceiverTexel& r = map.receivers().at(v, i, j);
        if (r.valid) out[0].image.pixels[px] = shade(r.position);
        const CasterTexel& c = map.casters()[k];
        if (c.valid) {
          out[1].image.pixels[px] = shade(c.position);
          out[2].image.pixels[px] = 0.5f * c.normal + 0.5f;
        }
        if (white > 0.0f) out[3].image.pixels[px] = map.texelIrradiance(k) / white;
      }
    }
  }
  return out;
}

}  // namespace prism

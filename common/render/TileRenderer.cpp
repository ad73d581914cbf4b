#include "render/TileRenderer.h"

#include <chrono>

namespace prism {

TileRenderer::TileRenderer(const Scene& scene, const LightTerms& terms)
    : scene_(scene), integrator_(scene, terms), sampler_(scene.settings().samplesPerPixel) {}

Color TileRenderer::renderPixel(int x, int y, RayCounters& rays) const {
  Pcg32 rng =
      Pcg32::forKey(scene_.settings().seed, static_cast<uint64_t>(x), static_cast<uint64_t>(y));
  Color sum(0.0f);
  for (int i = 0; i < sampler_.count(); ++i) {
    const Vec2 offset = sampler_.offset(i, rng);
    const Ray ray = scene_.camera().generateRay(static_cast<float>(x) + offset.x,
                                                static_cast<float>(y) + offset.y);
    ++rays.primary;
    sum += integrator_.radiance(ray, 0, Color(1.0f), rays);
  }
  return sum / static_cast<float>(sampler_.count());
}

TileResult TileRenderer::render(uint32_t tileIndex, const TileRect& rect) const {
  const auto start = std::chrono::steady_clock::now();
  TileResult result;
  result.tileIndex = tileIndex;
  result.rect = rect;
  result.pixels.resize(static_cast<size_t>(rect.pixelCount()));
  size_t i = 0;
  for (int y = rect.y; y < rect.y + rect.height; ++y) {
    for (int x = rect.x; x < rect.x + rect.width; ++x) {
      result.pixels[i++] = renderPixel(x, y, result.rays);
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace prism

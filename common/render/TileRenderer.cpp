#include "render/TileRenderer.h"

#include "render/DebugShading.h"
#include "util/Stopwatch.h"

namespace prism {

TileRenderer::TileRenderer(const Scene& scene, const LightTerms& terms)
    : scene_(scene),
      camera_(scene.camera()),
      seed_(scene.settings().seed),
      integrator_(scene, terms),
      sampler_(scene.settings().samplesPerPixel) {}

TileRenderer::TileRenderer(const Scene& scene, const RenderView& view, const LightTerms& terms)
    : scene_(scene),
      camera_(view.camera, view.width, view.height),
      seed_(view.seed),
      debugView_(view.debugView),
      integrator_(scene, terms),
      sampler_(view.samplesPerPixel, view.jitterSingleSample) {}

Color TileRenderer::renderPixel(int x, int y, RayCounters& rays) const {
  Pcg32 rng = Pcg32::forKey(seed_, static_cast<uint64_t>(x), static_cast<uint64_t>(y));
  Color sum(0.0f);
  for (int i = 0; i < sampler_.count(); ++i) {
    const Vec2 offset = sampler_.offset(i, rng);
    const Ray ray =
        camera_.generateRay(static_cast<float>(x) + offset.x, static_cast<float>(y) + offset.y);
    Color sample;
    if (debugView_ != DebugView::Image) {
      sample = debugColor(scene_, ray, debugView_, rays);
    } else {
      ++rays.primary;
      const RayDifferential differential =
          integrator_.usesDifferentials() ? camera_.pixelDifferential(ray) : RayDifferential{};
      sample = integrator_.radiance(ray, 0, Color(1.0f), rays, differential);
    }
    // One NaN or infinite sample would poison the pixel and every average it enters.
    if (isFinite(sample)) {
      sum += sample;
    } else {
      ++rays.nonFinite;
    }
  }
  const Color pixel = sum / static_cast<float>(sampler_.count());
  if (isFinite(pixel)) return pixel;
  ++rays.nonFinite;  // finite samples that summed past the float range
  return Color(0.0f);
}

TileResult TileRenderer::render(uint32_t tileIndex, const TileRect& rect,
                                const std::atomic<bool>* cancel) const {
  const auto start = SteadyClock::now();
  TileResult result;
  result.tileIndex = tileIndex;
  result.rect = rect;
  result.pixels.resize(static_cast<size_t>(rect.pixelCount()));
  size_t i = 0;
  for (int y = rect.y; y < rect.y + rect.height; ++y) {
    if (cancel && cancel->load(std::memory_order_relaxed)) break;
    for (int x = rect.x; x < rect.x + rect.width; ++x) {
      result.pixels[i++] = renderPixel(x, y, result.rays);
    }
  }
  result.seconds = secondsSince(start);
  return result;
}

}  // namespace prism

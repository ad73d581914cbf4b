#include "render/TileRenderer.h"

#include "render/RenderKernels.h"

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

TileResult TileRenderer::render(uint32_t tileIndex, const TileRect& rect,
                                const std::atomic<bool>* cancel,
                                const std::atomic<bool>* frameEnded) const {
  // The scene's instruction set, looked up per tile (a switch): a test may change it between.
  return renderKernels(scene_.instructionSet())
      .renderTile(*this, tileIndex, rect, cancel, frameEnded);
}

}  // namespace prism

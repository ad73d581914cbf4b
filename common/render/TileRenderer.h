// Renders one tile of the image on the calling thread. Each pixel draws from its own random
// stream keyed by (seed, x, y), so a pixel's value does not depend on the tile it belongs to,
// the thread that renders it or the order of tiles: images are bit-identical for any schedule.
#pragma once

#include <atomic>

#include "render/PixelSampler.h"
#include "render/RenderView.h"
#include "render/Tile.h"
#include "render/WhittedIntegrator.h"

namespace prism {

class TileRenderer {
 public:
  // terms: which light the tiles add up (direct, caustics), see render/RenderPass.h.
  explicit TileRenderer(const Scene& scene, const LightTerms& terms = {});
  // The viewer: the view's camera, image size, samples, seed and debug view replace the
  // scene's own.
  TileRenderer(const Scene& scene, const RenderView& view, const LightTerms& terms = {});

  // cancel, when given and set, ends the tile after the current row (an interrupted run); the
  // result is then incomplete and must be dropped.
  TileResult render(uint32_t tileIndex, const TileRect& rect,
                    const std::atomic<bool>* cancel = nullptr) const;

 private:
  Color renderPixel(int x, int y, RayCounters& rays) const;

  const Scene& scene_;
  Camera camera_;
  uint64_t seed_;
  DebugView debugView_ = DebugView::Image;
  WhittedIntegrator integrator_;
  PixelSampler sampler_;
};

}  // namespace prism

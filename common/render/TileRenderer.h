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

// How a tile's camera rays are traced: in packets of eight (4 × 2 pixel blocks,
// Scene::intersect8; their shadow rays and first reflection and refraction rays in packets too,
// see WhittedIntegrator::radiance8) or one at a time. The images are bit-identical. Debug views
// and integrators whose caustic estimate takes the pixel's footprint (photon gathers) always go
// one ray at a time.
enum class CameraRays { Packets, OneByOne };

class TileRenderer {
 public:
  // terms: which light the tiles add up (direct, caustics), see render/RenderPass.h.
  explicit TileRenderer(const Scene& scene, const LightTerms& terms = {});
  // The viewer: the view's camera, image size, samples, seed and debug view replace the
  // scene's own.
  TileRenderer(const Scene& scene, const RenderView& view, const LightTerms& terms = {});

  // cancel or frameEnded, when given and set, ends the tile after the current row (an
  // interrupted run; a frame that has ended); the result is then incomplete and must be dropped.
  TileResult render(uint32_t tileIndex, const TileRect& rect,
                    const std::atomic<bool>* cancel = nullptr,
                    const std::atomic<bool>* frameEnded = nullptr) const;

  // Packets by default; one at a time to compare against or to measure what packets buy.
  void setCameraRays(CameraRays mode) { cameraRays_ = mode; }

  // The render of a tile itself, one copy per instruction set (render/RenderKernels.h holds
  // their addresses; render/TileRendering.cpp). render() calls the scene's set.
  struct Kernels {
    static TileResult render(const TileRenderer& renderer, uint32_t tileIndex, const TileRect& rect,
                             const std::atomic<bool>* cancel, const std::atomic<bool>* frameEnded);
  };

 private:
  Color renderPixel(int x, int y, RayCounters& rays) const;
  // The differential of sample number `sample` of a pixel, its ray through the pixel's point
  // moved by offset: Camera::pixelDifferential, over the sample's stratum where there are several.
  RayDifferential sampleDifferential(const Ray& ray, int sample, const Vec2& offset) const;
  // The cone of a sample's camera ray: the pixel's, or its stratum's of several samples.
  RayCone sampleCone(const Ray& ray) const;
  // The pixels of a block of at most Scene::kPacketSize (columns x..x+columns-1 of rows
  // y..y+rows-1), each sample's camera rays traced as one packet; written to out in row order
  // with the given row stride.
  void renderBlock(int x, int y, int columns, int rows, Color* out, int outStride,
                   RayCounters& rays) const;
  // A sample as the pixel sums it: NaN or infinite samples are counted and add nothing.
  static void addSample(const Color& sample, Color& sum, RayCounters& rays);
  Color pixelValue(const Color& sum, RayCounters& rays) const;

  const Scene& scene_;
  Camera camera_;
  uint64_t seed_;
  DebugView debugView_ = DebugView::Image;
  WhittedIntegrator integrator_;
  PixelSampler sampler_;
  CameraRays cameraRays_ = CameraRays::Packets;
};

}  // namespace prism

// Renders one whole frame on this process: plans tiles, hands them to the worker pool and
// assembles the results. The single-process `prism render` runs exactly this.
#pragma once

#include <functional>

#include "image/ImageRgb.h"
#include "render/RayCounters.h"
#include "scene/Scene.h"

namespace prism {

struct FrameOptions {
  int threads = 0;   // 0: every available core
  int tileSize = 0;  // 0: automatic
  // Called on the rendering thread with (tiles done, tiles total), about ten times a second.
  std::function<void(size_t, size_t)> progress;
};

struct FrameResult {
  ImageRgb image;
  RayCounters rays;
  size_t tileCount = 0;
  int tileSize = 0;
  int threads = 0;
  double seconds = 0.0;            // wall time
  double busyThreadSeconds = 0.0;  // summed over tiles
};

FrameResult renderFrame(const Scene& scene, const FrameOptions& options);

}  // namespace prism

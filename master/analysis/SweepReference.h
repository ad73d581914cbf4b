// The image `prism sweep` scores every render against, and the same frame without caustics
// (for the caustic flux and the caustic region). Three kinds:
//   given        an image file (--reference FILE), the same size as the sweep's renders;
//   analytic     the closed form of flat-mirror caustics (caustics/MirrorCausticEstimator.h),
//                rendered through the same integrator, so only the caustic term differs;
//   progressive  progressive photon mapping at a high budget, cached next to the outputs with a
//                key of the scene and settings, with its own convergence: how far the estimate
//                after 1/16, 1/8, 1/4 and 1/2 of its passes still is from the final image.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "image/ImageError.h"
#include "scene/SceneDescription.h"

namespace prism {

struct ReferenceConvergence {
  int passes = 0;
  double seconds = 0.0;        // when that pass was done
  double regionRelRmse = 0.0;  // against the final image, in the caustic region
  double imageRelRmse = 0.0;   // against the final image, whole frame
};

struct ReferenceRequest {
  std::string spec = "auto";   // auto | analytic | progressive | an image file
  int passes = 64;             // progressive
  uint64_t photons = 1000000;  // progressive, per pass
  // progressive: the k of the per-photon radii (each photon's distance to its k-th nearest).
  // Far fewer than a render's 100: many passes average the noise of small radii away, but not
  // the blur of large ones
  // (docs/accuracy.md, "The reference").
  int k = 5;
  std::string cacheStem;  // progressive: <stem>.exr and <stem>.csv
  bool refresh = false;   // progressive: render even when the cache matches
  int threads = 0;
};

struct SweepReference {
  std::string kind;         // "given", "analytic" or "progressive"
  std::string description;  // one line for the chart and the summary
  bool cached = false;
  ImageRgb image;
  ImageRgb base;  // direct light only, the sweep's settings
  PixelMask region;
  std::vector<ReferenceConvergence> convergence;  // progressive only
};

// Renders, loads or reuses the reference for the scene (with the sweep's render settings).
// Throws std::runtime_error (std::invalid_argument for "analytic" on a scene without a closed
// form) with a message for the user. progress gets (label, done, total).
SweepReference makeSweepReference(
    const SceneDescription& scene, const ReferenceRequest& request,
    const std::function<void(const std::string&, size_t, size_t)>& progress = {});

// The frame without caustics: direct light at the description's settings.
ImageRgb renderWithoutCaustics(const SceneDescription& scene, int threads);

}  // namespace prism

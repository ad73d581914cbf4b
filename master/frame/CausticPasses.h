// Renders a frame with its caustics: the passes a scene's caustic settings call for, each
// with its photon map traced across the ranks (master/frame/PhotonPass.h), summed into one image.
//   none, or no caster any light can reach: one pass of direct light, no photons at all;
//   photon map:  one photon pass, then one frame with direct light and k-NN caustics;
//   caustic map: every rank builds the same caustic maps from the scene (no wire traffic), then
//                one frame with direct light and the maps' caustics;
//   progressive: one frame of direct light, then caustic-only passes, each with fresh photons
//                and a fixed gather radius that shrinks as r²(i+1) = r²(i)·(i + α)/(i + 1)
//                (Knaus & Zwicker 2011); the image is the direct frame plus the mean of the
//                caustic frames.
// Every pass draws from its own photon streams, so the image is bit-identical for any rank
// count, thread count or tile size (a time budget makes the pass count, and so the image,
// depend on speed). The budget bounds the whole run from FrameOptions::runStart.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "caustics/CausticMapEstimator.h"
#include "caustics/GatherRadius.h"
#include "caustics/PhotonMap.h"
#include "caustics/PhotonTracer.h"
#include "master/frame/FrameRenderer.h"
#include "master/frame/PhotonPass.h"

namespace prism {

struct CausticRunStats {
  CausticMethod method = CausticMethod::None;
  bool progressive = false;
  bool noCasters = false;  // photon mapping was asked for but no light reaches a caster
  uint64_t photonsPerPass = 0;
  int passes = 0;                    // photon passes traced
  PhotonPassStats photons;           // every photon pass added up (the largest map's bytes)
  double gatherRenderSeconds = 0.0;  // frames that gathered photons
  int k = 0;
  float firstRadius = 0.0f, lastRadius = 0.0f;  // gather radius (progressive) or k-NN cap
  // Progressive under a time budget (master/frame/PassBudget.h): whether it stopped a pass
  // from starting, the seconds into the run when it did, the longest pass and the write it
  // reserved.
  bool stoppedByBudget = false;
  double budgetStopSeconds = 0.0, longestPassSeconds = 0.0, budgetWriteSeconds = 0.0;
  CausticMapStats map;  // caustic mapping: summed over the lights (rank 0's build)
  double mapBuildSeconds = 0.0;
  CausticSettings settings;  // the run's, for the parameters the summary prints
};

struct CausticFrame {
  // Interrupted (frames.interrupted), image holds the tiles frames.tileDone marks; a
  // progressive run stopped between or during its caustic passes keeps every tile, with the
  // mean of the passes it finished (caustics.passes).
  ImageRgb image;
  FrameResult frames;  // every frame of the run added together (tiles, rays, busy time)
  CausticRunStats caustics;
  std::shared_ptr<const PhotonMap> lastMap;                // for the photon debug image
  std::shared_ptr<const CausticMapEstimator> causticMaps;  // for the caustic-map debug images
};

// (stage label, done, total), from the coordinating thread.
using PassProgress = std::function<void(const std::string&, size_t, size_t)>;

// Progressive runs: after each caustic pass, the passes done and the image so far (the direct
// frame plus the mean of those passes), from the coordinating thread. `prism sweep` scores the
// progressive estimate pass by pass with it.
using ProgressiveSnapshot = std::function<void(int passes, const ImageRgb& image)>;

// Every frame and photon pass of the run on the run's one dispatcher (and its link).
CausticFrame renderWithCaustics(WorkDispatcher& dispatcher, const FrameOptions& options,
                                const PassProgress& progress = {},
                                const ProgressiveSnapshot& snapshot = {});
// On this process alone, with a dispatcher of its own.
CausticFrame renderWithCaustics(const Scene& scene, const FrameOptions& options,
                                const PassProgress& progress = {},
                                const ProgressiveSnapshot& snapshot = {});

}  // namespace prism

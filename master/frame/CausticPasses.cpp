#include "master/frame/CausticPasses.h"

#include <algorithm>
#include <cmath>

#include "caustics/GatherRadius.h"
#include "caustics/PhotonGather.h"
#include "master/frame/PassBudget.h"
#include "util/Stopwatch.h"

namespace prism {
namespace {

// Adds one frame's work to the run's totals.
void addFrame(FrameResult& total, const FrameResult& f, bool first) {
  if (first) {
    total = f;
    return;
  }
  if (!total.firstTileAt) total.firstTileAt = f.firstTileAt;
  total.rays += f.rays;
  total.tileCount += f.tileCount;
  total.seconds += f.seconds;
  total.busyThreadSeconds += f.busyThreadSeconds;
  total.reissuedTiles += f.reissuedTiles;
  for (size_t r = 0; r < total.workers.size() && r < f.workers.size(); ++r) {
    total.workers[r] += f.workers[r];
  }
}

// The progressive estimate after `passes` caustic passes: direct light plus their mean.
ImageRgb progressiveImage(const ImageRgb& direct, const ImageRgb& causticSum, int passes) {
  ImageRgb image = direct;
  const float scale = 1.0f / static_cast<float>(std::max(passes, 1));
  for (size_t px = 0; px < image.pixels.size(); ++px)
    image.pixels[px] += causticSum.pixels[px] * scale;
  return image;
}

}  // namespace

namespace {

// One run's passes on one dispatcher: the frames, the photon passes between them, and the
// totals of both.
class CausticRun {
 public:
  CausticRun(WorkDispatcher& dispatcher, FrameOptions options, const PassProgress& progress)
      : dispatcher_(dispatcher),
        scene_(dispatcher.scene()),
        settings_(scene_.causticSettings()),
        options_(std::move(options)),
        progress_(progress),
        frameId_(options_.frameId),
        runStart_(options_.runStart.value_or(SteadyClock::now())) {
    CausticRunStats& stats = out_.caustics;
    stats.method = settings_.method;
    stats.progressive = settings_.progressive;
    stats.k = classicGather(settings_, 0.0f).k;  // with gather: auto, its largest k
    stats.settings = settings_;
  }

  CausticFrame causticMaps();
  CausticFrame photonMap(const ProgressiveSnapshot& snapshot);

 private:
  FrameResult frame(std::shared_ptr<const RenderPass> pass, const std::string& label) {
    options_.pass = std::move(pass);
    options_.frameId = frameId_++;
    options_.progress = [this, label](size_t done, size_t total) {
      if (progress_) progress_(label, done, total);
    };
    return renderFrame(dispatcher_, options_);
  }
  // A single frame is the run's image and its totals.
  CausticFrame single(std::shared_ptr<const RenderPass> pass, bool gathers) {
    FrameResult f = frame(std::move(pass), "render");
    if (gathers) out_.caustics.gatherRenderSeconds += f.seconds;
    out_.image = std::move(f.image);  // out_.frames keeps the counts, not a second copy
    addFrame(out_.frames, f, true);
    return std::move(out_);
  }
  // Traces pass `pass` across the ranks and returns rank 0's gather from its photons (the
  // ranks find the radii together).
  std::shared_ptr<const PhotonGather> photonPass(uint32_t pass, const std::string& label,
                                                 const PhotonGatherSettings& gather);
  CausticFrame progressive(const ProgressiveSnapshot& snapshot);

  WorkDispatcher& dispatcher_;
  const Scene& scene_;
  const CausticSettings& settings_;
  FrameOptions options_;
  const PassProgress& progress_;
  uint32_t frameId_;
  CausticFrame out_;
  std::unique_ptr<PhotonTracer> tracer_;
  float maxRadius_ = 0.0f;
  SteadyClock::time_point runStart_;
};

CausticFrame CausticRun::causticMaps() {
  // Built here on rank 0 and by each slave for itself (slave/): the maps depend on the scene
  // alone, so every rank's copy is bit-identical and nothing is sent.
  if (progress_) progress_("caustic map", 0, 1);
  const auto start = SteadyClock::now();
  auto maps = std::make_shared<const CausticMapEstimator>(scene_, dispatcher_.localThreads());
  CausticRunStats& stats = out_.caustics;
  stats.mapBuildSeconds = secondsSince(start);
  stats.map = maps->stats();
  stats.noCasters = maps->empty();
  out_.causticMaps = maps;
  return single(RenderPass::withCausticMaps(0, maps), true);
}

std::shared_ptr<const PhotonGather> CausticRun::photonPass(uint32_t pass, const std::string& label,
                                                           const PhotonGatherSettings& gather) {
  // Rank 0's share is sized by its threads, the slaves' by theirs.
  const int threads = dispatcher_.localThreads();
  if (progress_) progress_(label + " photons", 0, 1);
  PhotonPassStats p;
  auto estimator = runPhotonPass(*tracer_, pass, gather, threads, dispatcher_, p);
  out_.caustics.photons += p;
  ++out_.caustics.passes;
  return estimator;
}

CausticFrame CausticRun::photonMap(const ProgressiveSnapshot& snapshot) {
  CausticRunStats& stats = out_.caustics;
  if (settings_.method == CausticMethod::PhotonMap) {
    tracer_ = std::make_unique<PhotonTracer>(scene_, settings_.photons, settings_.maxBounces);
    stats.noCasters = !tracer_->hasWork();
    stats.photonsPerPass = tracer_->photonsPerPass();
  }
  // Nothing to trace: a plain frame, no photon cost.
  if (!tracer_ || !tracer_->hasWork()) return single(RenderPass::directOnly(0), false);
  maxRadius_ = settings_.maxRadius > 0.0f ? settings_.maxRadius : automaticMaxRadius(scene_);
  if (settings_.progressive) return progressive(snapshot);
  auto estimator = photonPass(0, "trace", classicGather(settings_, maxRadius_));
  out_.lastMap = estimator->sharedMap();
  stats.firstRadius = stats.lastRadius = maxRadius_;
  return single(RenderPass::withPhotons(0, true, std::move(estimator)), true);
}

// The direct frame, then caustic-only passes 1, 2, ...
CausticFrame CausticRun::progressive(const ProgressiveSnapshot& snapshot) {
  CausticRunStats& stats = out_.caustics;
  FrameResult direct = frame(RenderPass::directOnly(0), "direct light");
  addFrame(out_.frames, direct, true);
  if (direct.interrupted) {
    out_.image = direct.image;
    return std::move(out_);
  }
  ImageRgb causticSum(direct.image.width, direct.image.height);
  const PassBudget budget{settings_.timeBudgetSeconds,
                          budgetedWriteSeconds(causticSum.pixels.size())};
  stats.budgetWriteSeconds = budget.writeSeconds;
  PhotonGatherSettings gather;
  int done = 0;
  for (int i = 1; i <= settings_.passes; ++i) {
    const double elapsed = secondsSince(runStart_);
    if (!startsPass(budget, i, elapsed, stats.longestPassSeconds)) {
      stats.stoppedByBudget = true;
      stats.budgetStopSeconds = elapsed;
      break;
    }
    const auto passStart = SteadyClock::now();
    // Interrupted between passes: the image of the passes done is whole, so nothing is missing.
    if (options_.stopRequested && options_.stopRequested()) {
      out_.frames.interrupted = true;
      break;
    }
    const std::string label =
        "pass " + std::to_string(i) +
        (passesUntilBudget(settings_) ? std::string() : "/" + std::to_string(settings_.passes));
    gather = progressiveGather(settings_, maxRadius_, i, gather);
    // Per-photon radii: the cap, scaled as the radii are.
    if (i == 1) stats.firstRadius = gather.radius * gather.radiusScale;
    stats.lastRadius = gather.radius * gather.radiusScale;
    auto estimator = photonPass(static_cast<uint32_t>(i), label, gather);
    const std::shared_ptr<const PhotonMap> map = estimator->sharedMap();
    FrameResult f = frame(
        RenderPass::withPhotons(static_cast<uint32_t>(i), false, std::move(estimator)), label);
    if (f.interrupted) {  // a pass with missing tiles would darken them: keep the passes done
      out_.frames.interrupted = true;
      break;
    }
    stats.gatherRenderSeconds += f.seconds;
    for (size_t px = 0; px < causticSum.pixels.size(); ++px)
      causticSum.pixels[px] += f.image.pixels[px];
    addFrame(out_.frames, f, false);
    out_.lastMap = map;
    ++done;
    stats.longestPassSeconds = std::max(stats.longestPassSeconds, secondsSince(passStart));
    if (snapshot) snapshot(done, progressiveImage(direct.image, causticSum, done));
  }
  out_.image = progressiveImage(direct.image, causticSum, done);
  return std::move(out_);
}

}  // namespace

CausticFrame renderWithCaustics(WorkDispatcher& dispatcher, const FrameOptions& options,
                                const PassProgress& progress, const ProgressiveSnapshot& snapshot) {
  CausticRun run(dispatcher, options, progress);
  if (dispatcher.scene().causticSettings().method == CausticMethod::CausticMap) {
    return run.causticMaps();
  }
  return run.photonMap(snapshot);
}

CausticFrame renderWithCaustics(const Scene& scene, const FrameOptions& options,
                                const PassProgress& progress, const ProgressiveSnapshot& snapshot) {
  WorkDispatcher alone(scene, nullptr, options.distribution);
  return renderWithCaustics(alone, options, progress, snapshot);
}

}  // namespace prism

#include "master/runtime/CausticPasses.h"

#include <algorithm>
#include <cmath>

#include "caustics/GatherRadius.h"
#include "caustics/PhotonGather.h"
#include "master/runtime/PhotonPass.h"
#include "util/Parallel.h"
#include "util/Stopwatch.h"

namespace prism {
namespace {

// Adds one frame's work to the run's totals.
void addFrame(FrameResult& total, const FrameResult& f, bool first) {
  if (first) {
    total = f;
    return;
  }
  total.rays += f.rays;
  total.tileCount += f.tileCount;
  total.seconds += f.seconds;
  total.busyThreadSeconds += f.busyThreadSeconds;
  total.reissuedTiles += f.reissuedTiles;
  for (size_t r = 0; r < total.workers.size() && r < f.workers.size(); ++r) {
    RankStats& w = total.workers[r];
    const RankStats& o = f.workers[r];
    w.tiles += o.tiles;
    w.rays += o.rays;
    w.busySeconds += o.busySeconds;
    w.staleTiles += o.staleTiles;
    w.lostTiles += o.lostTiles;
    w.retired = w.retired || o.retired;
    if (o.threads > 0) w.threads = o.threads;
    if (o.buildSeconds > 0.0) w.buildSeconds = o.buildSeconds;
  }
}

void addPhotonStats(CausticRunStats& c, const PhotonPassStats& p) {
  c.trace += p.trace;
  c.traceSeconds += p.traceSeconds;
  c.buildSeconds += p.buildSeconds;
  c.distributeSeconds += p.distributeSeconds;
  c.radiiSeconds += p.radiiSeconds;
  c.mapBytes = std::max(c.mapBytes, p.mapBytes);
  c.sentBytes += p.sentBytes;
  const auto addByRank = [](std::vector<uint64_t>& total, const std::vector<uint64_t>& pass) {
    if (total.size() < pass.size()) total.resize(pass.size());
    for (size_t r = 0; r < pass.size(); ++r) total[r] += pass[r];
  };
  addByRank(c.photonsByRank, p.photonsByRank);
  addByRank(c.radiiByRank, p.radiiByRank);
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

std::shared_ptr<const RenderPass> causticMapPass(uint32_t index,
                                                 std::shared_ptr<const CausticMapEstimator> maps) {
  if (!maps || maps->empty())
    return std::make_shared<const RenderPass>(RenderPass{index, true, nullptr});
  return std::make_shared<const RenderPass>(RenderPass{index, true, std::move(maps), true});
}

CausticFrame renderWithCaustics(const Scene& scene, FrameOptions options, SlaveLink& link,
                                const PassProgress& progress, const ProgressiveSnapshot& snapshot) {
  const CausticSettings& settings = scene.causticSettings();
  CausticFrame out;
  CausticRunStats& stats = out.caustics;
  stats.method = settings.method;
  stats.progressive = settings.progressive;
  stats.k = classicGather(settings, 0.0f).k;  // with gather: auto, its largest k
  stats.settings = settings;
  uint32_t frameId = options.frameId;

  const auto frame = [&](std::shared_ptr<const RenderPass> pass, const std::string& label) {
    options.pass = std::move(pass);
    options.frameId = frameId++;
    options.progress = [&](size_t done, size_t total) {
      if (progress) progress(label, done, total);
    };
    return renderFrame(scene, options, link);
  };

  if (settings.method == CausticMethod::CausticMap) {
    // Built here on rank 0 and by each slave for itself (slave/SlaveLoop.cpp): the maps depend
    // on the scene alone, so every rank's copy is bit-identical and nothing is sent.
    if (progress) progress("caustic map", 0, 1);
    const auto start = SteadyClock::now();
    auto maps = std::make_shared<const CausticMapEstimator>(scene, options.distribution.threads);
    stats.mapBuildSeconds = secondsSince(start);
    stats.map = maps->stats();
    stats.noCasters = maps->empty();
    out.causticMaps = maps;
    auto pass = causticMapPass(0, maps);
    FrameResult f = frame(pass, "render");
    stats.gatherRenderSeconds += f.seconds;
    out.image = std::move(f.image);  // out.frames keeps the counts, not a second copy
    addFrame(out.frames, f, true);
    return out;
  }

  std::unique_ptr<PhotonTracer> tracer;
  if (settings.method == CausticMethod::PhotonMap) {
    tracer = std::make_unique<PhotonTracer>(scene, settings.photons, settings.maxBounces);
    stats.noCasters = !tracer->hasWork();
    stats.photonsPerPass = tracer->photonsPerPass();
  }
  if (!tracer || !tracer->hasWork()) {  // nothing to trace: a plain frame, no photon cost
    FrameResult f = frame(nullptr, "render");
    out.image = std::move(f.image);  // out.frames keeps the counts, not a second copy
    addFrame(out.frames, f, true);
    return out;
  }

  // Resolved here: the photon shares are sized by thread counts.
  const int threads =
      options.distribution.threads > 0 ? options.distribution.threads : availableCores();
  const float maxRadius =
      settings.maxRadius > 0.0f ? settings.maxRadius : automaticMaxRadius(scene);
  // Traces pass `pass` across the ranks and returns rank 0's gather from its photons (the ranks
  // find the radii together).
  const auto photonPass = [&](uint32_t pass, const std::string& label,
                              const PhotonGatherSettings& gather) {
    if (progress) progress(label + " photons", 0, 1);
    PhotonPassStats p;
    std::vector<Photon> photons = *tracePhotonPass(*tracer, pass, threads, link, p);
    auto estimator = gatherFromPhotons(std::move(photons), pass, gather, threads, link, p);
    addPhotonStats(stats, p);
    ++stats.passes;
    return estimator;
  };

  if (!settings.progressive) {
    auto estimator = photonPass(0, "trace", classicGather(settings, maxRadius));
    const std::shared_ptr<const PhotonMap> map = estimator->sharedMap();
    stats.firstRadius = stats.lastRadius = maxRadius;
    auto pass = std::make_shared<const RenderPass>(RenderPass{0, true, std::move(estimator)});
    FrameResult f = frame(pass, "render");
    stats.gatherRenderSeconds += f.seconds;
    out.image = std::move(f.image);  // out.frames keeps the counts, not a second copy
    addFrame(out.frames, f, true);
    out.lastMap = map;
    return out;
  }

  // Progressive: the direct frame, then caustic-only passes 1, 2, ...
  FrameResult direct =
      frame(std::make_shared<const RenderPass>(RenderPass{0, true, nullptr}), "direct light");
  addFrame(out.frames, direct, true);
  if (direct.interrupted) {
    out.image = direct.image;
    return out;
  }
  ImageRgb causticSum(direct.image.width, direct.image.height);
  const auto causticStart = SteadyClock::now();
  PhotonGatherSettings gather;
  int done = 0;
  for (int i = 1; i <= settings.passes; ++i) {
    if (i > 1 && settings.timeBudgetSeconds > 0.0 &&
        secondsSince(causticStart) >= settings.timeBudgetSeconds) {
      break;
    }
    // Interrupted between passes: the image of the passes done is whole, so nothing is missing.
    if (options.stopRequested && options.stopRequested()) {
      out.frames.interrupted = true;
      break;
    }
    const std::string label = "pass " + std::to_string(i) + "/" + std::to_string(settings.passes);
    gather = progressiveGather(settings, maxRadius, i, gather);
    // Per-photon radii: the cap, scaled as the radii are.
    if (i == 1) stats.firstRadius = gather.radius * gather.radiusScale;
    stats.lastRadius = gather.radius * gather.radiusScale;
    auto estimator = photonPass(static_cast<uint32_t>(i), label, gather);
    const std::shared_ptr<const PhotonMap> map = estimator->sharedMap();
    auto pass = std::make_shared<const RenderPass>(
        RenderPass{static_cast<uint32_t>(i), false, std::move(estimator)});
    FrameResult f = frame(pass, label);
    if (f.interrupted) {  // a pass with missing tiles would darken them: keep the passes done
      out.frames.interrupted = true;
      break;
    }
    stats.gatherRenderSeconds += f.seconds;
    for (size_t px = 0; px < causticSum.pixels.size(); ++px)
      causticSum.pixels[px] += f.image.pixels[px];
    addFrame(out.frames, f, false);
    out.lastMap = map;
    ++done;
    if (snapshot) snapshot(done, progressiveImage(direct.image, causticSum, done));
  }
  out.image = progressiveImage(direct.image, causticSum, done);
  return out;
}

CausticFrame renderWithCaustics(const Scene& scene, const FrameOptions& options,
                                const PassProgress& progress, const ProgressiveSnapshot& snapshot) {
  SlaveLink alone(nullptr, options.distribution);
  return renderWithCaustics(scene, options, alone, progress, snapshot);
}

}  // namespace prism

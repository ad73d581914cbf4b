// LiveRenderer's light terms: what each pass adds up, decided on the coordinator thread before
// the pass starts (master/live/LiveRenderer.h): direct light alone while moving, the caustic
// maps every rank builds from the scene, or a photon pass traced across the ranks (the first
// view's pass 1 kept and named again for later views).
#include <algorithm>

#include "caustics/CausticMapMemory.h"
#include "caustics/GatherRadius.h"
#include "caustics/PhotonGather.h"
#include "master/frame/PhotonPass.h"
#include "master/live/LivePassPlan.h"

namespace prism {

std::shared_ptr<const CausticMapEstimator> LiveRenderer::causticMaps(bool blur) {
  if (mapsRefusal_) throw ResourceLimitError(*mapsRefusal_);
  const std::lock_guard<std::mutex> lock(mapsMutex_);
  std::shared_ptr<const CausticMapEstimator>& maps = causticMaps_[blur];
  if (!maps) {
    causticMaps_.erase(!blur);  // frames still rendering with them hold their own reference
    const auto start = SteadyClock::now();
    maps = std::make_shared<const CausticMapEstimator>(
        scene_, causticMapSettings(scene_.causticSettings(), blur), dispatcher_.localThreads());
    mapBuildSeconds_[blur] = secondsSince(start);
  }
  return maps;
}

std::shared_ptr<const RenderPass> LiveRenderer::causticMapLight(const PassPlan& plan) {
  // Every rank builds the maps from the scene once per blur setting (a slave as soon as it has
  // a caustic-map scene, else when the first tile asks); they do not depend on the camera, so
  // every frame, a reduced one too, looks them up.
  const bool blur = plan.view.causticMapBlur;
  const std::shared_ptr<const CausticMapEstimator> maps = causticMaps(blur);
  double buildSeconds = 0.0;
  {
    const std::lock_guard<std::mutex> lock(mapsMutex_);
    buildSeconds = mapBuildSeconds_[blur];
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  if (plan.viewId == viewId_) {
    PhotonLiveStats& s = live_.photons;
    s.noCasters = maps->empty();
    s.mapResolution = scene_.causticSettings().mapResolution;
    s.mapViews = maps->stats().views;
    s.mapBlur = blur;
    s.mapBuildSeconds = buildSeconds;
  }
  if (maps->empty()) return nullptr;
  return RenderPass::withCausticMaps(plan.frame, maps);
}

std::shared_ptr<const RenderPass> LiveRenderer::passLight(const PassPlan& plan) {
  if (plan.view.debugView != DebugView::Image) return nullptr;  // debug views: no caustics
  if (plan.view.caustics == CausticMethod::CausticMap) return causticMapLight(plan);
  // Frames while moving show no photon-mapped caustics: a photon pass would delay them.
  if (plan.index == 0 || plan.view.caustics != CausticMethod::PhotonMap) return nullptr;
  const CausticSettings& c = scene_.causticSettings();
  const uint64_t budget = plan.view.photonsPerPass > 0 ? plan.view.photonsPerPass : c.photons;
  if (!tracer_ || tracerBudget_ != budget) {
    tracer_ = std::make_unique<PhotonTracer>(scene_, budget, c.maxBounces);
    tracerBudget_ = budget;
  }
  if (!tracer_->hasWork()) {
    const std::lock_guard<std::mutex> lock(mutex_);
    live_.photons.noCasters = true;
    return nullptr;  // like `prism render`: nothing to trace, a plain pass
  }
  PhotonPassStats p;
  std::shared_ptr<const PhotonMap> map;
  std::shared_ptr<const PhotonGather> estimator;
  PhotonGatherSettings gather;
  const bool reused = plan.index == 1 && firstPhotonPass_ && firstPhotonPass_->budget == budget;
  if (reused) {
    map = firstPhotonPass_->map;
    estimator = firstPhotonPass_->estimator;
    gather = estimator->settings();
    p = firstPhotonPass_->stats;
    p.distributeSeconds = 0.0;
    sendPhotonMapAgain(plan.frame, firstPhotonPass_->frame, link_);  // the slaves kept it too
  } else {
    gather = progressiveGather(c, maxRadius_, static_cast<int>(plan.index), gather_);
    estimator = runPhotonPass(*tracer_, plan.frame, gather, dispatcher_.localThreads(), dispatcher_,
                              p, plan.index == 1, &cancelPhotons_);
    if (!estimator) return nullptr;  // the camera moved: the pass is dropped before it starts
    map = estimator->sharedMap();
    if (plan.index == 1) firstPhotonPass_ = FirstPhotonPass{budget, plan.frame, map, estimator, p};
  }
  gather_ = gather;

  const std::lock_guard<std::mutex> lock(mutex_);
  if (plan.viewId == viewId_) {
    PhotonLiveStats& s = live_.photons;
    s.photonsPerPass = tracer_->photonsPerPass();
    ++s.passes;
    s.last = p;
    s.radius = gather.radius * gather.radiusScale;  // per-photon radii: their cap
    s.reused = reused;
  }
  return RenderPass::withPhotons(plan.frame, true, std::move(estimator));
}

}  // namespace prism

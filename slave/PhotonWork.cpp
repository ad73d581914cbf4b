#include "slave/PhotonWork.h"

#include <chrono>
#include <functional>
#include <stdexcept>

#include "caustics/CausticMapMemory.h"
#include "caustics/PhotonGather.h"
#include "caustics/PhotonRadii.h"
#include "transport/Transport.h"
#include "util/Stopwatch.h"

namespace prism {

PhotonWork::PhotonWork(const Scene& scene, int threads, Transport& transport,
                       const MemoryLimit& memoryLimit)
    : scene_(scene),
      threads_(threads),
      transport_(transport),
      mapsRefusal_(causticMapsRefusal(scene, memoryLimit)) {
  // A caustic-map scene: build the maps now, while rank 0 builds its own, rather than when
  // the first tile asks (which would put a second build on the frame's critical path).
  if (scene_.causticSettings().method == CausticMethod::CausticMap) {
    eagerMaps_ = std::async(std::launch::async, [this] {
      return std::make_shared<const CausticMapEstimator>(scene_, threads_);
    });
  }
}

void PhotonWork::start(const wire::PhotonJobMessage& job) {
  // Planned with the master's budget (the viewer may change it), so photon powers agree.
  if (!tracer_ || tracer_->photonsPerPass() != job.photonsPerPass) {
    if (running_.valid()) running_.wait();  // it may be tracing with the old tracer
    tracer_ = std::make_unique<PhotonTracer>(scene_, job.photonsPerPass,
                                             scene_.causticSettings().maxBounces);
  }
  run(job.pass, [this, job] {
    const auto start = SteadyClock::now();
    wire::PhotonShareMessage share{job.pass, job.first, job.count, {}, 0.0, {}};
    share.photons =
        tracePhotons(*tracer_, job.pass, job.first, job.count, threads_, &share.stats, &cancel_);
    share.seconds = secondsSince(start);
    return wire::encode(share);
  });
}

void PhotonWork::findRadii(const wire::PhotonRadiiJobMessage& job) {
  const PendingMap& p = pendingFor(job.pass, "radii job");
  run(job.pass, [this, job, map = p.map, gather = p.gather] {
    wire::PhotonRadiiShareMessage share{job.pass, job.first, {}};
    share.radii = photonRadiiShare(*map, gather.k, gather.radius, gather.automaticK, job.first,
                                   job.count, threads_, &cancel_);
    return wire::encode(share);
  });
}

void PhotonWork::cancel(uint32_t pass) {
  if (running_.valid() && runningPass_ == pass) cancel_ = true;
}

std::optional<std::vector<uint8_t>> PhotonWork::finished() {
  if (!running_.valid() ||
      running_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
    return std::nullopt;
  }
  return running_.get();
}

void PhotonWork::acceptMap(wire::PhotonMapMessage&& message) {
  auto map = std::make_shared<const PhotonMap>(std::move(message.photons));
  pending_.reset();
  if (PhotonGather::needsRadii(message.gather, map->size())) {
    pending_ = PendingMap{message.pass, std::move(map), message.gather, message.keep};
    return;
  }
  useGather(message.pass, std::make_shared<const PhotonGather>(std::move(map), message.gather),
            message.keep);
}

void PhotonWork::acceptRadii(wire::PhotonRadiiMessage&& message) {
  PendingMap& p = pendingFor(message.pass, "radii");
  useGather(
      p.pass,
      std::make_shared<const PhotonGather>(p.map, p.gather, std::move(message.radii), threads_),
      p.keep);
  pending_.reset();
}

void PhotonWork::reuseMap(const wire::PhotonMapAgainMessage& message) {
  if (!kept_ || keptPass_ != message.keptPass) {
    throw std::runtime_error("pass " + std::to_string(message.pass) +
                             " reuses the photon map of pass " + std::to_string(message.keptPass) +
                             ", which this rank does not keep");
  }
  useGather(message.pass, kept_, false);
}

std::shared_ptr<const RenderPass> PhotonWork::pass(const PassTerms& terms, bool blur) {
  if (terms.source == CausticSource::CausticMap) return causticMapPass(terms.index, blur);
  const bool caustics = terms.source == CausticSource::PhotonMap;
  if (caustics && (!caustics_ || mapPass_ != terms.index)) {
    throw std::runtime_error("tile of pass " + std::to_string(terms.index) +
                             " needs a photon map this rank has not received");
  }
  std::shared_ptr<const RenderPass>& cached = passes_[{terms.direct, caustics}];
  if (!cached || cached->index != terms.index) {
    cached = caustics ? RenderPass::withPhotons(terms.index, terms.direct, caustics_)
                      : RenderPass::directOnly(terms.index);
  }
  return cached;
}

// Caustic mapping: built here from the scene, the same maps as rank 0's; no message.
std::shared_ptr<const RenderPass> PhotonWork::causticMapPass(uint32_t index, bool blur) {
  if (mapsRefusal_) throw ResourceLimitError(*mapsRefusal_);
  const std::shared_ptr<const CausticMapEstimator>& maps = causticMaps(blur);
  std::shared_ptr<const RenderPass>& cached = mapPasses_[blur];
  if (!cached || cached->index != index) cached = RenderPass::withCausticMaps(index, maps);
  return cached;
}

std::shared_ptr<const CausticMapEstimator>& PhotonWork::causticMaps(bool blur) {
  std::shared_ptr<const CausticMapEstimator>& maps = causticMaps_[blur];
  if (maps) return maps;
  // One set of maps at a time, as the memory check counts: the other blur setting's go (tiles
  // still rendering with them hold their own reference).
  causticMaps_.erase(!blur);
  std::erase_if(mapPasses_, [blur](const auto& entry) { return entry.first != blur; });
  if (eagerMaps_.valid()) {
    std::shared_ptr<const CausticMapEstimator> eager = eagerMaps_.get();  // the scene's blur
    if (blur) maps = std::move(eager);
  }
  if (!maps) {
    maps = std::make_shared<const CausticMapEstimator>(
        scene_, causticMapSettings(scene_.causticSettings(), blur), threads_);
  }
  return maps;
}

void PhotonWork::wait() {
  if (running_.valid()) running_.wait();
  if (eagerMaps_.valid()) eagerMaps_.wait();
}

// Runs a share's work (tracing, or finding radii) on a thread of its own, so the main thread
// keeps its heartbeat going; work() returns the message for rank 0. One at a time: rank 0 asks
// again only after a pass is done or dropped (a dropped one stops within a chunk).
void PhotonWork::run(uint32_t pass, Work work) {
  if (running_.valid()) running_.wait();
  runningPass_ = pass;
  cancel_ = false;
  running_ = std::async(std::launch::async,
                        [this, work = std::move(work)]() -> std::optional<std::vector<uint8_t>> {
                          std::vector<uint8_t> message = work();
                          transport_.wake();  // the main thread sends it, or forgets it
                          if (cancel_) return std::nullopt;
                          return message;
                        });
}

PhotonWork::PendingMap& PhotonWork::pendingFor(uint32_t pass, const char* what) {
  if (!pending_ || pending_->pass != pass) {
    throw std::runtime_error(std::string(what) + " for the photon map of pass " +
                             std::to_string(pass) + ", which this rank has not received");
  }
  return *pending_;
}

void PhotonWork::useGather(uint32_t pass, std::shared_ptr<const CausticEstimator> gather,
                           bool keep) {
  mapPass_ = pass;
  caustics_ = std::move(gather);
  passes_.clear();
  if (keep) {
    kept_ = caustics_;
    keptPass_ = pass;
  }
}

}  // namespace prism

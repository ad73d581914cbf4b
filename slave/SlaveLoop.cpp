#include "slave/SlaveLoop.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <thread>
#include <utility>

#include "caustics/CausticMapEstimator.h"
#include "caustics/CausticMapMemory.h"
#include "caustics/PhotonGather.h"
#include "caustics/PhotonRadii.h"
#include "caustics/PhotonTracer.h"
#include "cluster/TileWorkerPool.h"
#include "scene/GeometryMemory.h"
#include "scene/Scene.h"
#include "slave/JobQueue.h"
#include "transport/Transport.h"
#include "util/InterruptSignal.h"
#include "util/Parallel.h"
#include "util/ProcessStart.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"
#include "wire/TileJobWire.h"

namespace prism {
namespace {

using Clock = SteadyClock;

constexpr double kInterruptedShutdownSeconds = 0.8;
// The longest the message loop sleeps without news: the bound on noticing Ctrl-C or rank 0's
// silence. Messages, finished tiles and photon shares wake it at once.
constexpr double kIdleCheckSeconds = 0.1;

// Finished tiles, with the frame they belong to, waiting for the main thread, the only one
// that calls MPI. A finished tile wakes the main thread's wait for messages, so it leaves at
// once.
class Outbox {
 public:
  explicit Outbox(Transport& session) : session_(session) {}
  // displayExposure: the frame's RenderView::displayExposure (0: send radiance).
  void add(uint32_t frame, TileResult&& tile, float displayExposure) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      tiles_.push_back({frame, std::move(tile), displayExposure});
    }
    session_.wake();
  }
  std::vector<wire::TileResultMessage> take() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(tiles_, {});
  }

 private:
  Transport& session_;
  std::mutex mutex_;
  std::vector<wire::TileResultMessage> tiles_;
};

// The caustic side of a slave: traces the photon shares and finds the shares of photon radii
// the master asks for (on a thread of its own, so the main thread keeps its heartbeat going),
// holds the photon map of the current pass for the tiles that need it, and builds the caustic
// maps.
class PhotonWork {
 public:
  // memoryLimit: this rank's, against which caustic maps the viewer switches on are checked.
  PhotonWork(const Scene& scene, int threads, Transport& session, const MemoryLimit& memoryLimit)
      : scene_(scene),
        threads_(threads),
        session_(session),
        mapsRefusal_(causticMapsRefusal(scene, memoryLimit)) {
    // A caustic-map scene: build the maps now, while rank 0 builds its own, rather than when
    // the first tile asks (which would put a second build on the frame's critical path).
    if (scene_.causticSettings().method == CausticMethod::CausticMap) {
      eagerMaps_ = std::async(std::launch::async, [this] {
        return std::make_shared<const CausticMapEstimator>(scene_, threads_);
      });
    }
  }

  void start(const wire::PhotonJobMessage& job) {
    // Planned with the master's budget (the viewer may change it), so photon powers agree.
    if (!tracer_ || tracer_->photonsPerPass() != job.photonsPerPass) {
      if (running_.valid()) running_.wait();  // it may be tracing with the old tracer
      tracer_ = std::make_unique<PhotonTracer>(scene_, job.photonsPerPass,
                                               scene_.causticSettings().maxBounces);
    }
    run(job.pass, [this, job] {
      const auto start = Clock::now();
      wire::PhotonShareMessage share{job.pass, job.first, job.count, {}, 0.0, {}};
      share.photons =
          tracePhotons(*tracer_, job.pass, job.first, job.count, threads_, &share.stats, &cancel_);
      share.seconds = secondsSince(start);
      return wire::encode(share);
    });
  }

  // This rank's share of the radii of the map waiting for them.
  void findRadii(const wire::PhotonRadiiJobMessage& job) {
    const PendingMap& p = pendingFor(job.pass, "radii job");
    run(job.pass, [this, job, map = p.map, gather = p.gather] {
      wire::PhotonRadiiShareMessage share{job.pass, job.first, {}};
      share.radii = photonRadiiShare(*map, gather.k, gather.radius, gather.automaticK, job.first,
                                     job.count, threads_, &cancel_);
      return wire::encode(share);
    });
  }

  // Rank 0 dropped this pass: the share being traced, or whose radii are being found, stops
  // within a chunk of photons and is not sent, so this rank's threads are free for the next
  // frame's tiles at once.
  void cancel(uint32_t pass) {
    if (running_.valid() && runningPass_ == pass) cancel_ = true;
  }

  // The finished share's message, once there is one (none for a cancelled pass).
  std::optional<std::vector<uint8_t>> finished() {
    if (!running_.valid() ||
        running_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
      return std::nullopt;
    }
    return running_.get();
  }

  // A map whose gather needs per-photon radii waits for them (PhotonRadii), after this rank
  // finds its share if asked (PhotonRadiiJob); any other gathers at once.
  void acceptMap(wire::PhotonMapMessage&& message) {
    auto map = std::make_shared<const PhotonMap>(std::move(message.photons));
    pending_.reset();
    if (PhotonGather::needsRadii(message.gather, map->size())) {
      pending_ = PendingMap{message.pass, std::move(map), message.gather, message.keep};
      return;
    }
    useGather(message.pass, std::make_shared<const PhotonGather>(std::move(map), message.gather),
              message.keep);
  }

  void acceptRadii(wire::PhotonRadiiMessage&& message) {
    PendingMap& p = pendingFor(message.pass, "radii");
    useGather(
        p.pass,
        std::make_shared<const PhotonGather>(p.map, p.gather, std::move(message.radii), threads_),
        p.keep);
    pending_.reset();
  }

  // The kept map serves another pass: its radii and discs are not found again.
  void reuseMap(const wire::PhotonMapAgainMessage& message) {
    if (!kept_ || keptPass_ != message.keptPass) {
      throw std::runtime_error(
          "pass " + std::to_string(message.pass) + " reuses the photon map of pass " +
          std::to_string(message.keptPass) + ", which this rank does not keep");
    }
    useGather(message.pass, kept_, false);
  }

  // The render pass a tile job names; throws when it needs a photon map this rank lacks.
  // `blur`: the current view's caustic-map blur switch.
  std::shared_ptr<const RenderPass> pass(uint32_t index, uint8_t terms, bool blur) {
    const bool direct = (terms & wire::kTermDirect) != 0;
    if (terms & wire::kTermCausticMap) {
      // Caustic mapping: built here from the scene, the same maps as rank 0's; no message.
      if (mapsRefusal_) throw ResourceLimitError(*mapsRefusal_);
      std::shared_ptr<const CausticMapEstimator>& maps = causticMaps_[blur];
      if (!maps) {
        // One set of maps at a time, as the memory check counts: the other blur setting's go
        // (tiles still rendering with them hold their own reference).
        causticMaps_.erase(!blur);
        std::erase_if(mapPasses_, [blur](const auto& entry) { return entry.first.second != blur; });
        if (eagerMaps_.valid()) {
          std::shared_ptr<const CausticMapEstimator> eager = eagerMaps_.get();  // the scene's blur
          if (blur) maps = std::move(eager);
        }
      }
      if (!maps) {
        maps = std::make_shared<const CausticMapEstimator>(
            scene_, causticMapSettings(scene_.causticSettings(), blur), threads_);
      }
      std::shared_ptr<const RenderPass>& cached = mapPasses_[{terms, blur}];
      if (!cached || cached->index != index) {
        cached = std::make_shared<const RenderPass>(RenderPass{index, direct, maps, true});
      }
      return cached;
    }
    const bool caustics = terms & wire::kTermCaustics;
    if (caustics && (!caustics_ || mapPass_ != index)) {
      throw std::runtime_error("tile of pass " + std::to_string(index) +
                               " needs a photon map this rank has not received");
    }
    std::shared_ptr<const RenderPass>& cached = passes_[terms];
    if (!cached || cached->index != index) {
      cached = std::make_shared<const RenderPass>(
          RenderPass{index, direct, caustics ? caustics_ : nullptr});
    }
    return cached;
  }

  void wait() {
    if (running_.valid()) running_.wait();
    if (eagerMaps_.valid()) eagerMaps_.wait();
  }

 private:
  // Runs a share's work (tracing, or finding radii) on a thread of its own, so the main thread
  // keeps its heartbeat going; work() returns the message for rank 0. One at a time: rank 0
  // asks again only after a pass is done or dropped (a dropped one stops within a chunk).
  template <class Work>
  void run(uint32_t pass, Work work) {
    if (running_.valid()) running_.wait();
    runningPass_ = pass;
    cancel_ = false;
    running_ =
        std::async(std::launch::async, [this, work]() -> std::optional<std::vector<uint8_t>> {
          std::vector<uint8_t> message = work();
          session_.wake();  // the main thread sends it, or forgets it
          if (cancel_) return std::nullopt;
          return message;
        });
  }

  // A photon map received, its gather waiting for the radii.
  struct PendingMap {
    uint32_t pass = 0;
    std::shared_ptr<const PhotonMap> map;
    PhotonGatherSettings gather;
    bool keep = false;
  };

  PendingMap& pendingFor(uint32_t pass, const char* what) {
    if (!pending_ || pending_->pass != pass) {
      throw std::runtime_error(std::string(what) + " for the photon map of pass " +
                               std::to_string(pass) + ", which this rank has not received");
    }
    return *pending_;
  }

  void useGather(uint32_t pass, std::shared_ptr<const CausticEstimator> gather, bool keep) {
    mapPass_ = pass;
    caustics_ = std::move(gather);
    passes_.clear();
    if (keep) {
      kept_ = caustics_;
      keptPass_ = pass;
    }
  }

  const Scene& scene_;
  int threads_;
  Transport& session_;
  std::unique_ptr<PhotonTracer> tracer_;
  std::future<std::optional<std::vector<uint8_t>>> running_;
  uint32_t runningPass_ = 0;
  std::atomic<bool> cancel_{false};
  std::optional<PendingMap> pending_;
  uint32_t mapPass_ = 0;
  std::shared_ptr<const CausticEstimator> caustics_;  // the photon map of pass mapPass_
  // The last map sent with keep, as a gather, and its pass: the viewer names it again for every
  // later view's pass 1 (master/runtime/LiveRenderer.h), where sending and finding its radii again
  // held this rank's tiles up after every pause of the camera.
  std::shared_ptr<const CausticEstimator> kept_;
  uint32_t keptPass_ = 0;
  std::map<uint8_t, std::shared_ptr<const RenderPass>> passes_;
  std::optional<std::string> mapsRefusal_;  // why caustic maps cannot be built here, if so
  // Caustic maps by blur switch, built on first use and kept until the other setting's are
  // built: they depend on the scene alone.
  std::map<bool, std::shared_ptr<const CausticMapEstimator>> causticMaps_;
  std::future<std::shared_ptr<const CausticMapEstimator>> eagerMaps_;  // with the scene's blur
  std::map<std::pair<uint8_t, bool>, std::shared_ptr<const RenderPass>> mapPasses_;
};

// After a failure the slave still waits (bounded) for the master's shutdown, so the job ends
// through rank 0's clear message rather than this rank vanishing.
void awaitShutdown(Transport& session, double timeoutSeconds) {
  const auto start = Clock::now();
  while (secondsSince(start) < timeoutSeconds) {
    const auto incoming = session.waitForMessage(0.1);
    if (!incoming) continue;
    try {
      if (wire::decodeMessage(incoming->bytes.data(), incoming->bytes.size()).type ==
          wire::MessageType::Shutdown) {
        session.send(0,
                     wire::encode(wire::ShutdownMessage{}));  // acknowledged: the master may finish
        return;
      }
    } catch (const wire::WireError&) {
    }
  }
}

}  // namespace

SlaveEnd runSlave(Transport& session, const DistributionOptions& options,
                  const MemoryLimit& memoryLimit) {
  const double startSeconds = secondsSinceProcessStart().value_or(-1.0);  // before any work
  installInterruptHandlers();
  std::vector<uint8_t> bytes;
  try {
    session.broadcast(bytes, options.masterTimeoutSeconds);
  } catch (const TransportError& e) {
    std::fprintf(stderr, "prism: rank %d: %s\n", session.rank(), e.what());
    return {1, true};
  }

  std::unique_ptr<Scene> scene;
  try {
    const wire::Message message = wire::decodeMessage(bytes.data(), bytes.size());
    // Rank 0 broadcasts an error instead of a scene when it cannot read the file; it reports it.
    if (message.type == wire::MessageType::Error) return {1};
    const auto buildStart = Clock::now();
    SceneDescription description = wire::decodeScene(message);
    // Rank 0 checked the scene against its own limit; this rank may be a smaller machine.
    checkGeometryFits(description, memoryLimit);
    scene =
        std::make_unique<Scene>(description, std::exchange(description.environment, std::nullopt));
    checkCausticMapsFit(*scene, memoryLimit);  // before any map is built
    const int threads = options.threads > 0 ? options.threads : availableCores();
    session.send(0, wire::encode(wire::ReadyMessage{secondsSince(buildStart), threads, startSeconds,
                                                    session.setUpSeconds()}));
  } catch (const std::exception& e) {
    session.send(
        0, wire::encode(wire::ErrorMessage{std::string("cannot build the scene: ") + e.what()}));
    awaitShutdown(session, options.masterTimeoutSeconds);
    return {1};
  }

  JobQueue jobs;
  Outbox outbox(session);
  TileWorkerPool pool(*scene, options.threads);
  const bool slow =
      options.fault.appliesTo(session.rank()) && options.fault.kind == FaultInjection::Kind::Slow;
  pool.start([&] { return jobs.pop(); },
             [&](const TileJob& job, TileResult&& tile) {
               if (slow) {  // the render thread stays taken, as on a slower machine
                 std::this_thread::sleep_for(std::chrono::duration<double>(kSlowTileDelaySeconds));
               }
               outbox.add(job.frame, std::move(tile), job.view ? job.view->displayExposure : 0.0f);
             });
  PhotonWork photons(*scene, options.threads > 0 ? options.threads : availableCores(), session,
                     memoryLimit);

  const bool hang =
      options.fault.appliesTo(session.rank()) && options.fault.kind == FaultInjection::Kind::Hang;
  const bool drop = options.fault.appliesTo(session.rank()) &&
                    options.fault.kind == FaultInjection::Kind::DropTiles;
  // The message loop and the heartbeat thread share the transport and the frame's counts under
  // one lock (MPI is called from one thread at a time). The loop lets go of it for anything
  // long (a wait, building caustic maps or a photon kd-tree), so the heartbeat never stops
  // while this rank is alive, and the master never takes a busy slave for a dead one.
  std::mutex shared;
  std::condition_variable beatStop;
  bool stopBeating = false;
  std::atomic<bool> masterGone{false};
  // The frames still running, by id; ids only grow. A View (the viewer) starts a frame and names
  // the oldest one still running (the viewer pipelines its frames); a job of a later frame
  // without a View (the passes of `prism render`) ends every earlier one. Work of a frame that
  // has ended is stale.
  struct FrameWork {
    std::shared_ptr<const RenderView> view;  // the viewer's; `prism render` uses the scene's
    uint64_t received = 0;                   // jobs of this frame
    std::set<uint32_t> held;                 // its tiles received, not yet returned
    // Set when the frame ends: its tiles being rendered stop after their row.
    std::shared_ptr<std::atomic<bool>> ended = std::make_shared<std::atomic<bool>>(false);
  };
  std::map<uint32_t, FrameWork> frames;
  // Ends the frames [first, last): their queued tiles are dropped by the caller, the ones being
  // rendered stop (a camera move must not wait for the tiles of a view nobody sees any more).
  const auto endFrames = [&](auto first, auto last) {
    for (auto f = first; f != last; ++f) *f->second.ended = true;
    frames.erase(first, last);
  };
  // The heartbeat keeps a slave busy with long tiles from being taken for dead, and lets the
  // master spot tiles this rank lost.
  std::thread heartbeat([&] {
    std::unique_lock<std::mutex> lock(shared);
    while (!beatStop.wait_for(lock, std::chrono::duration<double>(kHeartbeatSeconds),
                              [&] { return stopBeating; })) {
      if (hang) continue;
      std::vector<wire::ProgressMessage> progress;  // one per running frame; frame 0: none yet
      for (const auto& [id, work] : frames) {
        progress.push_back({id, work.received, {work.held.begin(), work.held.end()}});
      }
      if (progress.empty()) progress.push_back({});
      for (const wire::ProgressMessage& p : progress) {
        if (!session.send(0, wire::encode(p))) masterGone = true;
      }
    }
  });
  const auto stopHeartbeat = [&] {
    {
      const std::lock_guard<std::mutex> lock(shared);
      stopBeating = true;
    }
    beatStop.notify_all();
    if (heartbeat.joinable()) heartbeat.join();
  };
  bool shutdownReceived = false;
  bool masterSilent = false;
  bool interrupted = false;
  auto lastHeard = Clock::now();
  int exitCode = 0;
  try {
    std::unique_lock<std::mutex> lock(shared);
    // Runs f without the lock: f waits, or builds something big, while the heartbeat may send.
    const auto unlocked = [&lock](auto&& f) {
      lock.unlock();
      struct Relock {
        std::unique_lock<std::mutex>& lock;
        ~Relock() { lock.lock(); }
      } relock{lock};
      return f();
    };
    for (;;) {
      if (pool.failed()) break;
      if (interruptRequested()) {
        interrupted = true;
        break;
      }
      bool masterReachable = !masterGone;
      for (wire::TileResultMessage& result : outbox.take()) {
        const auto work = frames.find(result.frame);
        if (work == frames.end()) continue;  // finished after the viewer moved on: stale
        work->second.held.erase(result.result.tileIndex);
        masterReachable = session.send(0, wire::encode(result)) && masterReachable;
      }
      if (std::optional<std::vector<uint8_t>> share = photons.finished()) {
        masterReachable = session.send(0, std::move(*share)) && masterReachable;
      }
      if (!masterReachable) {
        std::fprintf(stderr, "prism: rank %d: rank 0 is gone, stopping\n", session.rank());
        exitCode = 1;
        masterSilent = true;
        break;
      }
      // Poll, else sleep (without the lock: the heartbeat may send meanwhile) until a message
      // may have come, a tile or photon share finished, or the idle bound passes.
      auto incoming = session.poll();
      if (!incoming) {
        unlocked([&] { session.awaitActivity(kIdleCheckSeconds); });
        incoming = session.poll();
      }
      if (!incoming) {
        if (secondsSince(lastHeard) > options.masterTimeoutSeconds) {
          std::fprintf(stderr, "prism: rank %d: no word from rank 0 for %.0f s, giving up\n",
                       session.rank(), options.masterTimeoutSeconds);
          exitCode = 1;
          masterSilent = true;
          break;
        }
        continue;
      }
      lastHeard = Clock::now();
      const wire::Message message =
          wire::decodeMessage(incoming->bytes.data(), incoming->bytes.size());
      if (message.type == wire::MessageType::Shutdown) {
        shutdownReceived = true;
        break;
      }
      if (message.type == wire::MessageType::View) {
        wire::ViewMessage next = wire::decode<wire::ViewMessage>(message);
        endFrames(frames.begin(), frames.lower_bound(next.liveFrom));
        jobs.dropBefore(next.liveFrom);  // tiles of frames nobody wants any more
        FrameWork& work = frames[next.frame];
        work = FrameWork{};
        work.view = std::make_shared<const RenderView>(std::move(next.view));
        continue;
      }
      if (message.type == wire::MessageType::Echo) {  // a link probe: straight back
        session.send(0, incoming->bytes);
        continue;
      }
      if (message.type == wire::MessageType::PhotonJob) {
        if (hang) continue;
        // Waits for a share still being traced.
        unlocked([&] { photons.start(wire::decode<wire::PhotonJobMessage>(message)); });
        continue;
      }
      if (message.type == wire::MessageType::PhotonCancel) {
        photons.cancel(wire::decode<wire::PhotonCancelMessage>(message).pass);
        continue;
      }
      if (message.type == wire::MessageType::PhotonMap) {
        // Builds the kd-tree.
        unlocked([&] { photons.acceptMap(wire::decode<wire::PhotonMapMessage>(message)); });
        continue;
      }
      if (message.type == wire::MessageType::PhotonRadiiJob) {
        if (hang) continue;
        // Waits for a share still being finished.
        unlocked([&] { photons.findRadii(wire::decode<wire::PhotonRadiiJobMessage>(message)); });
        continue;
      }
      if (message.type == wire::MessageType::PhotonRadii) {
        // Builds the disc tree.
        unlocked([&] { photons.acceptRadii(wire::decode<wire::PhotonRadiiMessage>(message)); });
        continue;
      }
      if (message.type == wire::MessageType::PhotonMapAgain) {
        photons.reuseMap(wire::decode<wire::PhotonMapAgainMessage>(message));
        continue;
      }
      if (message.type != wire::MessageType::TileJob) continue;
      const wire::TileJobMessage job = wire::decode<wire::TileJobMessage>(message);
      auto work = frames.find(job.frame);
      if (work == frames.end()) {
        if (!frames.empty() && job.frame < frames.rbegin()->first) continue;  // ended already
        endFrames(frames.begin(), frames.end());  // a later frame of `prism render`
        work = frames.emplace(job.frame, FrameWork{}).first;
      }
      FrameWork& frame = work->second;
      ++frame.received;
      if (options.fault.appliesTo(session.rank()) &&
          options.fault.kind == FaultInjection::Kind::Crash) {
        std::_Exit(9);  // dies without MPI_Finalize, like a killed process
      }
      if (hang || (drop && frame.received % 2 == 0)) continue;
      frame.held.insert(job.tileIndex);  // with the count: no heartbeat sees it received, not held
      // The first tile of a caustic-map pass may build the maps.
      std::shared_ptr<const RenderPass> pass = unlocked([&] {
        return photons.pass(job.pass, job.terms, !frame.view || frame.view->causticMapBlur);
      });
      TileJob tile = tileJobFromMessage(job, frame.view, std::move(pass));
      tile.frameEnded = frame.ended;
      jobs.push(std::move(tile));
    }
  } catch (const std::exception& e) {
    stopHeartbeat();
    session.send(0, wire::encode(wire::ErrorMessage{e.what()}));
    exitCode = 1;
  }
  stopHeartbeat();
  jobs.clear();
  jobs.close();
  pool.cancel();  // nobody will take a tile still being rendered: stop it after its row
  photons.wait();
  try {
    pool.join();
  } catch (const std::exception& e) {
    session.send(
        0, wire::encode(wire::ErrorMessage{std::string("render thread failed: ") + e.what()}));
    awaitShutdown(session, options.masterTimeoutSeconds);
    return {1};
  }
  if (shutdownReceived) {
    session.send(0, wire::encode(wire::ShutdownMessage{}));  // acknowledged: the master may finish
  } else if (interrupted) {
    // Usually every rank got the signal (mpiexec sends SIGTERM to all) and rank 0 is writing
    // its partial frame: wait for its shutdown a little, well inside mpiexec's one second
    // before SIGKILL. A slave interrupted alone tells rank 0, which ends the run with an error.
    session.send(
        0, wire::encode(wire::ErrorMessage{std::string("stopped by ") + interruptSignalName()}));
    awaitShutdown(session, kInterruptedShutdownSeconds);
    // SIGTERM comes from mpiexec ending the job: MPI_Finalize would wait for the SIGKILL.
    if (interruptSignalName() == std::string("SIGTERM")) std::_Exit(kInterruptedExitCode);
    return {kInterruptedExitCode};
  } else if (!masterSilent) {
    awaitShutdown(session, options.masterTimeoutSeconds);  // after an error this rank reported
  }
  return {exitCode, masterSilent};
}

}  // namespace prism

#include "slave/SlaveLoop.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <set>
#include <utility>

#include "scene/Scene.h"
#include "slave/JobQueue.h"
#include "slave/TileWorkerPool.h"
#include "transport/MpiSession.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {
namespace {

using Clock = SteadyClock;

// Finished tiles, with the frame they belong to, waiting for the main thread, the only one
// that calls MPI.
class Outbox {
 public:
  void add(uint32_t frame, TileResult&& tile) {
    const std::lock_guard<std::mutex> lock(mutex_);
    tiles_.push_back({frame, std::move(tile)});
  }
  std::vector<wire::TileResultMessage> take() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(tiles_, {});
  }

 private:
  std::mutex mutex_;
  std::vector<wire::TileResultMessage> tiles_;
};

// After a failure the slave still waits (bounded) for the master's shutdown, so the job ends
// through rank 0's clear message rather than this rank vanishing.
void awaitShutdown(MpiSession& session, double timeoutSeconds) {
  const auto start = Clock::now();
  while (secondsSince(start) < timeoutSeconds) {
    const auto incoming = session.waitForMessage(0.1);
    if (!incoming) continue;
    try {
      if (wire::decodeMessage(incoming->bytes.data(), incoming->bytes.size()).type ==
          wire::MessageType::Shutdown) {
        session.send(0, wire::encodeShutdown());  // acknowledged: the master may finish
        return;
      }
    } catch (const wire::WireError&) {
    }
  }
}

}  // namespace

int runSlave(MpiSession& session, const SlaveOptions& options) {
  std::vector<uint8_t> bytes;
  try {
    session.broadcast(bytes, options.masterTimeoutSeconds);
  } catch (const TransportError& e) {
    std::fprintf(stderr, "prism: rank %d: %s\n", session.rank(), e.what());
    return 1;
  }

  std::unique_ptr<Scene> scene;
  try {
    const wire::Message message = wire::decodeMessage(bytes.data(), bytes.size());
    // Rank 0 broadcasts an error instead of a scene when it cannot read the file; it reports it.
    if (message.type == wire::MessageType::Error) return 1;
    const auto buildStart = Clock::now();
    scene = std::make_unique<Scene>(wire::decodeScene(message));
    const int threads = options.threads > 0 ? options.threads : availableCores();
    session.send(0, wire::encodeReady({secondsSince(buildStart), threads}));
  } catch (const std::exception& e) {
    session.send(0, wire::encodeError({std::string("cannot build the scene: ") + e.what()}));
    awaitShutdown(session, options.masterTimeoutSeconds);
    return 1;
  }

  JobQueue jobs;
  Outbox outbox;
  TileWorkerPool pool(*scene, options.threads);
  pool.start(
      [&] { return jobs.pop(); },
      [&](const TileJob& job, TileResult&& tile) { outbox.add(job.frame, std::move(tile)); });

  const bool hang =
      options.fault.appliesTo(session.rank()) && options.fault.kind == FaultInjection::Kind::Hang;
  const bool drop = options.fault.appliesTo(session.rank()) &&
                    options.fault.kind == FaultInjection::Kind::DropTiles;
  constexpr double kHeartbeatSeconds = 0.5;
  uint64_t received = 0;
  std::set<uint32_t> held;  // received, not yet returned
  auto lastHeartbeat = Clock::now();
  bool shutdownReceived = false;
  bool masterSilent = false;
  auto lastHeard = Clock::now();
  int exitCode = 0;
  // The viewer's current frame and what it renders; `prism render` sends no View and its jobs
  // are all frame 0 with the scene's own camera.
  uint32_t frame = 0;
  std::shared_ptr<const RenderView> view;
  try {
    for (;;) {
      if (pool.failed()) break;
      bool masterReachable = true;
      for (wire::TileResultMessage& result : outbox.take()) {
        if (result.frame != frame) continue;  // finished after the viewer moved on: stale
        held.erase(result.result.tileIndex);
        masterReachable = session.send(0, wire::encodeTileResult(result)) && masterReachable;
      }
      // The heartbeat keeps a slave busy with long tiles from being taken for dead, and lets
      // the master spot tiles this rank lost.
      if (!hang && secondsSince(lastHeartbeat) > kHeartbeatSeconds) {
        const wire::ProgressMessage progress{received, {held.begin(), held.end()}};
        masterReachable = session.send(0, wire::encodeProgress(progress)) && masterReachable;
        lastHeartbeat = Clock::now();
      }
      if (!masterReachable) {
        std::fprintf(stderr, "prism: rank %d: rank 0 is gone, stopping\n", session.rank());
        exitCode = 1;
        masterSilent = true;
        break;
      }
      const auto incoming = session.waitForMessage(0.002);
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
        wire::ViewMessage next = wire::decodeView(message);
        frame = next.frame;
        view = std::make_shared<const RenderView>(std::move(next.view));
        jobs.clear();  // tiles of earlier frames nobody wants any more
        held.clear();
        continue;
      }
      if (message.type != wire::MessageType::TileJob) continue;
      const wire::TileJobMessage job = wire::decodeTileJob(message);
      ++received;
      if (job.frame != frame) continue;  // a job of a frame already ended
      if (options.fault.appliesTo(session.rank()) &&
          options.fault.kind == FaultInjection::Kind::Crash) {
        std::_Exit(9);  // dies without MPI_Finalize, like a killed process
      }
      if (hang || (drop && received % 2 == 0)) continue;
      held.insert(job.tileIndex);
      jobs.push({job.tileIndex, job.rect, job.frame, view});
    }
  } catch (const std::exception& e) {
    session.send(0, wire::encodeError({e.what()}));
    exitCode = 1;
  }
  jobs.clear();
  jobs.close();
  try {
    pool.join();
  } catch (const std::exception& e) {
    session.send(0, wire::encodeError({std::string("render thread failed: ") + e.what()}));
    awaitShutdown(session, options.masterTimeoutSeconds);
    return 1;
  }
  if (shutdownReceived) {
    session.send(0, wire::encodeShutdown());  // acknowledged: the master may finish
  } else if (!masterSilent) {
    awaitShutdown(session, options.masterTimeoutSeconds);  // after an error this rank reported
  }
  return exitCode;
}

}  // namespace prism

// What a slave holds once its scene is built, and what its message handlers work on: the
// scene, the frames it is rendering, the queue of tile jobs and the render threads that take
// them, the outbox of finished tiles, the photon work and the heartbeat. The message loop and
// the heartbeat share the transport and the frames under one lock, which the loop holds
// (loopLock) except where it waits or builds something big (unlocked()).
#pragma once

#include <memory>
#include <mutex>

#include "cluster/DistributionOptions.h"
#include "cluster/TileWorkerPool.h"
#include "scene/Scene.h"
#include "slave/FrameBook.h"
#include "slave/Heartbeat.h"
#include "slave/JobQueue.h"
#include "slave/Outbox.h"
#include "slave/PhotonWork.h"
#include "util/MemorySize.h"
#include "util/ThreadCount.h"

namespace prism {

class Transport;

struct SlaveWork {
  // Starts the render threads and the heartbeat; the rank's threads render its tiles and do its
  // photon work.
  SlaveWork(Transport& transport, std::unique_ptr<const Scene> scene, ThreadCount threads,
            const MemoryLimit& memoryLimit);
  ~SlaveWork();  // stops whatever still runs
  SlaveWork(const SlaveWork&) = delete;
  SlaveWork& operator=(const SlaveWork&) = delete;

  // Stops the heartbeat, drops the queued tiles, abandons the ones being rendered and waits
  // for every thread; rethrows a render thread's failure. Call without loopLock.
  void stop();

  // Runs f without the loop's lock: f waits, or builds something big, while the heartbeat may
  // send.
  template <class F>
  auto unlocked(F&& f) {
    loopLock.unlock();
    struct Relock {
      std::unique_lock<std::mutex>& lock;
      ~Relock() { lock.lock(); }
    } relock{loopLock};
    return f();
  }

  Transport& transport;
  const std::unique_ptr<const Scene> scene;
  std::mutex shared;  // the transport and the frames, between the loop and the heartbeat
  std::unique_lock<std::mutex> loopLock{shared, std::defer_lock};
  FrameBook frames;
  JobQueue jobs;
  Outbox outbox;
  PhotonWork photons;
  TileWorkerPool pool;
  Heartbeat heartbeat;
  bool shutdownReceived = false;  // the master's Shutdown came (acknowledged once stopped)
};

}  // namespace prism

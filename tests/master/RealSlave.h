// A real slave (runSlave, one render thread) on a thread of its own over the loopback, for tests
// of rank 0 against the slave's actual loop.
#pragma once

#include <chrono>
#include <thread>
#include <vector>

#include "cluster/DistributionOptions.h"
#include "master/dispatch/JobInstructionSet.h"
#include "master/dispatch/SlaveLink.h"
#include "scene/SceneDescription.h"
#include "slave/SlaveLoop.h"
#include "transport/LoopbackTransport.h"
#include "wire/Messages.h"

namespace prism::test {

// Runs rank `rank` of `network` until it ends; its exit code lands in *exitCode (join first).
// memoryLimit: the slave's own (--memory-limit on that rank).
inline std::thread startRealSlave(LoopbackNetwork& network, int rank, int* exitCode,
                                  MemoryLimit memoryLimit = {}) {
  return std::thread([&network, rank, exitCode, memoryLimit] {
    DistributionOptions options;
    options.threads = 1;
    options.masterTimeoutSeconds = 30.0;
    *exitCode = runSlave(network.endpoint(rank), options, memoryLimit).exitCode;
  });
}

// Rank 0's side of the start of a job whose slaves have started: their Hellos, the job's
// instruction set chosen from them (the best all run), the scene broadcast with it, every
// slave's SceneAccepted and the go-ahead to build (master/dispatch/DispatchSession.cpp). A slave
// that refuses the scene is told so (an Error broadcast) and std::runtime_error thrown.
inline void sendSceneAsRankZero(LoopbackNetwork& network, SceneDescription d) {
  Transport& master = network.endpoint(0);
  d.render.instructionSet = chooseJobInstructionSet(&master, d.render.instructionSet, 10.0).chosen;
  std::vector<uint8_t> bytes = wire::encodeScene(d);
  master.broadcast(bytes, 10.0);
  try {
    firstOfEachSlave<wire::SceneAcceptedMessage>(master, 10.0, "is silent");
  } catch (const std::runtime_error&) {
    bytes = wire::encode(wire::ErrorMessage{"a slave refused the scene"});
    master.broadcast(bytes, 10.0);
    throw;
  }
  bytes = wire::encode(wire::BuildGeometryMessage{});
  master.broadcast(bytes, 10.0);
}

// A real slave on rank 1 of `network` that has been sent the scene, as rank 0 sends it.
inline std::thread startRealSlaveWithScene(LoopbackNetwork& network, const SceneDescription& d,
                                           int* exitCode, const MemoryLimit& memoryLimit = {}) {
  std::thread slave = startRealSlave(network, 1, exitCode, memoryLimit);
  sendSceneAsRankZero(network, d);
  return slave;
}

// A two-rank loopback job whose rank 1 is a real slave sent the scene; the test plays rank 0.
// The slave is joined at the end even when a test stops early (it leaves at Shutdown, or on
// its own after rank 0's silence).
class RealSlaveJob {
 public:
  explicit RealSlaveJob(const SceneDescription& d)
      : slave_(startRealSlaveWithScene(network_, d, &exitCode_)) {}
  ~RealSlaveJob() {
    if (slave_.joinable()) slave_.join();
  }
  Transport& master() { return network_.endpoint(0); }
  // Whether the slave said Ready (its scene built) within 10 s.
  bool ready();
  // Waits for the slave to end; its exit code.
  int join() {
    slave_.join();
    return exitCode_;
  }

 private:
  LoopbackNetwork network_{2};
  int exitCode_ = -1;
  std::thread slave_;
};

// The types of the messages rank 0 receives, in order, until one of `type` (the last then) or
// until `seconds` pass.
inline std::vector<wire::MessageType> messagesUntil(Transport& master, wire::MessageType type,
                                                    double seconds) {
  std::vector<wire::MessageType> seen;
  const auto start = std::chrono::steady_clock::now();
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() <
         seconds) {
    const auto incoming = master.waitForMessage(0.05);
    if (!incoming) continue;
    seen.push_back(wire::decodeMessage(incoming->bytes).type);
    if (seen.back() == type) break;
  }
  return seen;
}

// Rank 0 drops photon pass `pass` (PhotonCancel) and shuts the slave down: what the slave sent
// until it acknowledged (Shutdown, the last), and how long that took.
struct CancelledPass {
  std::vector<wire::MessageType> seen;
  double seconds = 0.0;
};
inline CancelledPass cancelPassAndShutDown(Transport& master, uint32_t pass, double seconds) {
  master.send(1, wire::encode(wire::PhotonCancelMessage{pass}));
  master.send(1, wire::encode(wire::ShutdownMessage{}));
  const auto start = std::chrono::steady_clock::now();
  CancelledPass c;
  c.seen = messagesUntil(master, wire::MessageType::Shutdown, seconds);
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return c;
}

inline bool RealSlaveJob::ready() {
  const std::vector<wire::MessageType> seen =
      messagesUntil(master(), wire::MessageType::Ready, 10.0);
  return !seen.empty() && seen.back() == wire::MessageType::Ready;
}

}  // namespace prism::test

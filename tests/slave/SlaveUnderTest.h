// The real slave session (runSlave) as rank 1 of a two-rank loopback job, on a thread of its
// own, while the test plays rank 0 message by message: it broadcasts a scene, sends jobs and
// reads what the slave sends back. The slave's handlers are tested through the messages it
// answers with, over the same Transport the MPI runs use.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <thread>
#include <vector>

#include "cluster/DistributionOptions.h"
#include "parse/SceneLoader.h"
#include "render/TileRenderer.h"
#include "scene/Scene.h"
#include "slave/SlaveLoop.h"
#include "transport/LoopbackTransport.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism::test {

// One render thread, and a rank 0 that may stay silent a while (tests shorten it).
inline DistributionOptions slaveOptions(double masterTimeoutSeconds = 30.0) {
  DistributionOptions options;
  options.threads = 1;
  options.masterTimeoutSeconds = masterTimeoutSeconds;
  return options;
}

// The default scene (a mesh, glass, a mirror, a cube map), small.
inline SceneDescription smallScene() {
  SceneDescription d = loadScene(PRISM_SOURCE_DIR "/scenes/default.yaml");
  d.render.width = 64;
  d.render.height = 48;
  d.render.samplesPerPixel = 1;
  return d;
}

// A glass ball's caustic on a floor under a point light: a photon pass in a fraction of a second.
inline SceneDescription causticScene() {
  SceneDescription d = loadScene(PRISM_SOURCE_DIR "/scenes/caustic-glass-sphere.yaml");
  d.render.width = 48;
  d.render.height = 36;
  d.render.samplesPerPixel = 1;
  return d;
}

inline bool samePixels(const std::vector<Color>& a, const std::vector<Color>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Color)) == 0;
}

class SlaveUnderTest {
 public:
  explicit SlaveUnderTest(DistributionOptions options = slaveOptions())
      : thread_([this, options] { end_ = runSlave(network_.endpoint(1), options); }) {}
  // Ends a slave still running: an error instead of a scene if none was sent (the slave then
  // leaves at once), else a Shutdown.
  ~SlaveUnderTest() {
    if (!broadcast_) broadcastBytes(wire::encode(wire::ErrorMessage{"the test sent no scene"}));
    if (thread_.joinable()) {
      master().send(1, wire::encode(wire::ShutdownMessage{}));
      thread_.join();
    }
  }

  Transport& master() { return network_.endpoint(0); }
  LoopbackNetwork& network() { return network_; }

  void broadcast(const SceneDescription& d) { broadcastBytes(wire::encodeScene(d)); }
  // As rank 0 does: the slave's Hello first (master/dispatch/JobInstructionSet.h), kept apart
  // from seen(), then the broadcast; then, unless the bytes were an Error (the slave stops at
  // once), the slave's answer (kept in seen()) and the plan: `plan` when it accepted (by
  // default the go-ahead to build), else an Error.
  void broadcastBytes(std::vector<uint8_t> bytes, std::vector<uint8_t> plan = {}) {
    broadcastAlone(std::move(bytes));
    try {
      if (wire::decodeMessage(raw_broadcast_).type == wire::MessageType::Error) return;
    } catch (const wire::WireError&) {  // not even an envelope: the slave refuses it
    }
    const std::optional<wire::Message> answer = nextAnswer();
    if (answer && answer->type == wire::MessageType::SceneAccepted) {
      if (plan.empty()) plan = wire::encode(wire::BuildGeometryMessage{});
    } else {
      plan = wire::encode(wire::ErrorMessage{"the slave refused the scene"});
    }
    master().broadcast(plan, 10.0);
  }
  // The slave's answer to the scene: SceneAccepted or an Error, within 10 s.
  std::optional<wire::Message> nextAnswer() {
    const auto start = SteadyClock::now();
    while (secondsSince(start) < 10.0) {
      const auto incoming = master().waitForMessage(0.05);
      if (!incoming) continue;
      raw_.push_back(incoming->bytes);
      wire::Message message = wire::decodeMessage(incoming->bytes);
      seen_.push_back(message.type);
      return message;
    }
    return std::nullopt;
  }
  // The broadcast alone, after the Hello: a test that answers for rank 0 itself.
  void broadcastAlone(std::vector<uint8_t> bytes) {
    raw_broadcast_ = bytes;
    if (const auto incoming = master().waitForMessage(10.0)) {
      const wire::Message message = wire::decodeMessage(incoming->bytes);
      if (message.type == wire::MessageType::Hello) {
        hello_ = wire::decode<wire::HelloMessage>(message);
      } else {
        seen_.push_back(message.type);
      }
    }
    broadcast_ = true;
    master().broadcast(bytes, 10.0);
  }
  // The slave's Hello, once a broadcast took it.
  const std::optional<wire::HelloMessage>& hello() const { return hello_; }
  void send(std::vector<uint8_t> bytes) { master().send(1, std::move(bytes)); }

  // The next message of `type` the slave sends within timeoutSeconds; every message read on the
  // way is kept in seen().
  std::optional<wire::Message> next(wire::MessageType type, double timeoutSeconds = 30.0) {
    const auto start = SteadyClock::now();
    while (secondsSince(start) < timeoutSeconds) {
      const auto incoming = master().waitForMessage(0.05);
      if (!incoming) continue;
      raw_.push_back(incoming->bytes);
      wire::Message message = wire::decodeMessage(incoming->bytes);
      seen_.push_back(message.type);
      if (message.type == type) return message;
    }
    return std::nullopt;
  }
  // Ready after the scene, as rank 0 waits for it.
  bool ready() { return next(wire::MessageType::Ready).has_value(); }

  // Shuts the slave down; the messages it sent until its acknowledgement (the last of them).
  std::vector<wire::MessageType> shutDown() {
    const size_t before = seen_.size();
    send(wire::encode(wire::ShutdownMessage{}));
    next(wire::MessageType::Shutdown);
    return {seen_.begin() + static_cast<long>(before), seen_.end()};
  }

  // Waits for the session to end; how it ended.
  SlaveEnd join() {
    thread_.join();
    return end_;
  }

  const std::vector<wire::MessageType>& seen() const { return seen_; }
  const std::vector<std::vector<uint8_t>>& raw() const { return raw_; }
  size_t count(wire::MessageType type) const {
    return static_cast<size_t>(std::count(seen_.begin(), seen_.end(), type));
  }

 private:
  LoopbackNetwork network_{2};
  bool broadcast_ = false;
  std::vector<uint8_t> raw_broadcast_;
  std::optional<wire::HelloMessage> hello_;
  SlaveEnd end_{-1};
  std::vector<wire::MessageType> seen_;
  std::vector<std::vector<uint8_t>> raw_;
  std::thread thread_;  // last: starts once the rest is built
};

}  // namespace prism::test

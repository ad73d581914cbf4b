// A slave played by the test, message by message, over the loopback transport: it can answer
// late, twice, out of order, lose a tile, fall silent or keep heartbeating without working, so
// the master's side of the protocol is tested in one process. Its tiles are rendered exactly
// as a real slave renders them, so images can be compared bit for bit.
#pragma once

#include <atomic>
#include <optional>
#include <set>
#include <thread>
#include <vector>

#include "render/TileRenderer.h"
#include "scene/Scene.h"
#include "transport/Transport.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {

class ScriptedSlave {
 public:
  ScriptedSlave(Transport& transport, const Scene& scene) : transport_(transport), scene_(scene) {}

  void ready(int threads = 1) {
    transport_.send(0, wire::encode(wire::ReadyMessage{0.01, threads}));
  }

  // The next tile job, up to timeoutSeconds; a View before it sets the frame and view its tiles
  // render with. Other messages (photon jobs and maps) are skipped.
  std::optional<wire::TileJobMessage> nextJob(double timeoutSeconds = 10.0) {
    const auto start = SteadyClock::now();
    while (secondsSince(start) < timeoutSeconds) {
      const auto incoming = transport_.waitForMessage(0.01);
      if (!incoming) continue;
      const wire::Message message = wire::decodeMessage(incoming->bytes);
      if (message.type == wire::MessageType::Shutdown) {
        shutdown_ = true;
        return std::nullopt;
      }
      if (message.type == wire::MessageType::View) {
        wire::ViewMessage view = wire::decode<wire::ViewMessage>(message);
        frame_ = view.frame;
        view_ = view.view;
        received_ = 0;
        held_.clear();
        continue;
      }
      if (message.type != wire::MessageType::TileJob) continue;
      const wire::TileJobMessage job = wire::decode<wire::TileJobMessage>(message);
      if (job.frame != frame_) {
        frame_ = job.frame;
        received_ = 0;
        held_.clear();
      }
      ++received_;
      held_.insert(job.tileIndex);
      return job;
    }
    return std::nullopt;
  }

  // The next message of this type, up to timeoutSeconds; others are skipped.
  std::optional<wire::Message> waitFor(wire::MessageType type, double timeoutSeconds = 10.0) {
    const auto start = SteadyClock::now();
    while (secondsSince(start) < timeoutSeconds) {
      const auto incoming = transport_.waitForMessage(0.01);
      if (!incoming) continue;
      wire::Message message = wire::decodeMessage(incoming->bytes);
      if (message.type == type) return message;
    }
    return std::nullopt;
  }

  // The job's tile, rendered as a slave renders it (direct light; the view when there is one).
  wire::TileResultMessage render(const wire::TileJobMessage& job) const {
    const TileRenderer renderer = view_ ? TileRenderer(scene_, *view_) : TileRenderer(scene_);
    return {job.frame, renderer.render(job.tileIndex, job.rect)};
  }

  void deliver(const wire::TileResultMessage& tile) {
    held_.erase(tile.result.tileIndex);
    transport_.send(0, wire::encode(tile));
  }
  // The slave no longer holds this tile and never delivers it.
  void lose(uint32_t tile) { held_.erase(tile); }
  // What a real slave's heartbeat says: its frame, the jobs of it received, the tiles held.
  void heartbeat() {
    transport_.send(
        0, wire::encode(wire::ProgressMessage{frame_, received_, {held_.begin(), held_.end()}}));
  }
  void send(std::vector<uint8_t> bytes) { transport_.send(0, std::move(bytes)); }

  // Drains messages until the master's Shutdown (answered, as a real slave does) or the time
  // is up.
  void awaitShutdown(double timeoutSeconds = 10.0) {
    const auto start = SteadyClock::now();
    while (!shutdown_ && secondsSince(start) < timeoutSeconds) {
      const auto incoming = transport_.waitForMessage(0.01);
      if (incoming && wire::decodeMessage(incoming->bytes).type == wire::MessageType::Shutdown) {
        shutdown_ = true;
      }
    }
    if (shutdown_) transport_.send(0, wire::encode(wire::ShutdownMessage{}));
  }

  uint32_t frame() const { return frame_; }

 private:
  Transport& transport_;
  const Scene& scene_;
  uint32_t frame_ = 0;
  std::optional<RenderView> view_;
  uint64_t received_ = 0;
  std::set<uint32_t> held_;
  bool shutdown_ = false;
};

}  // namespace prism

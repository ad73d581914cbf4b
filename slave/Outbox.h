// Finished tiles, with the frame they belong to, waiting for the slave's main thread, the only
// one that sends (the render threads hand them over here). A finished tile wakes the main
// thread's wait for messages, so it leaves at once.
#pragma once

#include <cstdint>
#include <mutex>
#include <utility>
#include <vector>

#include "transport/Transport.h"
#include "wire/Messages.h"

namespace prism {

class Outbox {
 public:
  explicit Outbox(Transport& transport) : transport_(transport) {}

  // displayExposure: the frame's RenderView::displayExposure (0: send radiance).
  void add(uint32_t frame, TileResult&& tile, float displayExposure) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      tiles_.push_back({frame, std::move(tile), displayExposure});
    }
    transport_.wake();
  }

  std::vector<wire::TileResultMessage> take() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(tiles_, {});
  }

 private:
  Transport& transport_;
  std::mutex mutex_;
  std::vector<wire::TileResultMessage> tiles_;
};

}  // namespace prism

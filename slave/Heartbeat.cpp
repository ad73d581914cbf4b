#include "slave/Heartbeat.h"

#include <chrono>

#include "cluster/DistributionOptions.h"
#include "slave/FrameBook.h"
#include "transport/Transport.h"
#include "wire/Messages.h"

namespace prism {

Heartbeat::Heartbeat(Transport& transport, std::mutex& shared, const FrameBook& frames)
    : transport_(transport), shared_(shared), frames_(frames), thread_([this] { beat(); }) {}

Heartbeat::~Heartbeat() {
  stop();
}

void Heartbeat::stop() {
  {
    const std::lock_guard<std::mutex> lock(shared_);
    stopping_ = true;
  }
  stopped_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void Heartbeat::beat() {
  std::unique_lock<std::mutex> lock(shared_);
  while (!stopped_.wait_for(lock, std::chrono::duration<double>(kHeartbeatSeconds),
                            [this] { return stopping_; })) {
    for (const wire::ProgressMessage& p : frames_.progress()) {
      if (!transport_.send(0, wire::encode(p))) masterGone_ = true;
    }
  }
}

}  // namespace prism

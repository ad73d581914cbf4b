#include "slave/FaultInjectingTransport.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <utility>

namespace prism {
namespace {

using Kind = FaultInjection::Kind;
using Type = wire::MessageType;

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The message, or nothing when it is malformed (then it passes untouched: the rank reports it).
std::optional<wire::Message> decoded(const std::vector<uint8_t>& bytes) {
  try {
    return wire::decodeMessage(bytes);
  } catch (const wire::WireError&) {
    return std::nullopt;
  }
}

// The roles the message list gives (wire/Messages.h).
bool isWork(Type type) {
  return wire::kindOf(type).role == wire::Role::Work;
}

bool isAnswer(Type type) {
  return wire::kindOf(type).role == wire::Role::Answer;
}

}  // namespace

FaultInjectingTransport::FaultInjectingTransport(Transport& inner, FaultInjection::Kind kind,
                                                 Clock clock)
    : inner_(inner), kind_(kind), clock_(clock ? std::move(clock) : Clock(steadySeconds)) {}

bool FaultInjectingTransport::send(int dest, std::vector<uint8_t> bytes) {
  const std::lock_guard<std::mutex> lock(mutex_);
  releaseDue();
  std::optional<std::vector<uint8_t>> out = outgoing(dest, std::move(bytes));
  const bool sent = !out || inner_.send(dest, std::move(*out));
  return sent && !std::exchange(releaseFailed_, false);
}

size_t FaultInjectingTransport::progressSends() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    releaseDue();
  }
  return inner_.progressSends();
}

std::optional<IncomingMessage> FaultInjectingTransport::poll() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    releaseDue();
  }
  return firstAdmitted(inner_.poll());
}

std::optional<IncomingMessage> FaultInjectingTransport::waitForMessage(double timeoutSeconds) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    releaseDue();
  }
  return firstAdmitted(inner_.waitForMessage(std::min(timeoutSeconds, secondsUntilDue())));
}

void FaultInjectingTransport::awaitActivity(double timeoutSeconds) {
  inner_.awaitActivity(std::min(timeoutSeconds, secondsUntilDue()));
}

void FaultInjectingTransport::abortJob(int exitCode) {
  inner_.abortJob(exitCode);
  std::abort();  // not reached: abortJob ends the job
}

size_t FaultInjectingTransport::heldBack() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return held_.size();
}

std::optional<IncomingMessage> FaultInjectingTransport::firstAdmitted(
    std::optional<IncomingMessage> incoming) {
  while (incoming && !admit(incoming->bytes)) incoming = inner_.poll();
  return incoming;
}

bool FaultInjectingTransport::admit(const std::vector<uint8_t>& bytes) {
  const std::optional<wire::Message> message = decoded(bytes);
  if (!message) return true;
  switch (kind_) {
    case Kind::Hang:
      return !isWork(message->type);
    case Kind::Crash:
    case Kind::CrashOnPhotons:
      if (message->type == (kind_ == Kind::Crash ? Type::TileJob : Type::PhotonJob)) {
        std::_Exit(9);  // dies without MPI_Finalize, like a killed process
      }
      return true;
    case Kind::DropTiles: {
      if (message->type != Type::TileJob) return true;
      const uint32_t frame = wire::decode<wire::TileJobMessage>(*message).frame;
      const std::lock_guard<std::mutex> lock(mutex_);
      if (++tileJobs_[frame] % 2 != 0) return true;
      ++dropped_[frame];
      return false;
    }
    default:
      return true;
  }
}

std::optional<std::vector<uint8_t>> FaultInjectingTransport::outgoing(
    int dest, std::vector<uint8_t>&& bytes) {
  const std::optional<wire::Message> message = decoded(bytes);
  if (!message) return std::move(bytes);
  if (kind_ == Kind::Hang && isAnswer(message->type)) return std::nullopt;
  if (kind_ == Kind::DropTiles || kind_ == Kind::Slow) {
    if (message->type == Type::Progress) return rewriteProgress(*message);
  }
  if (kind_ != Kind::Slow) return std::move(bytes);
  if (message->type == Type::Ready) {
    lanes_.assign(
        static_cast<size_t>(std::max(1, wire::decode<wire::ReadyMessage>(*message).threads)), 0.0);
  } else if (message->type == Type::TileResult) {
    holdBack(dest, *message, std::move(bytes));
    return std::nullopt;
  }
  return std::move(bytes);
}

// Drop: the tiles swallowed were received, as far as rank 0 can tell. Slow: the results held
// back are still held.
std::vector<uint8_t> FaultInjectingTransport::rewriteProgress(const wire::Message& message) const {
  wire::ProgressMessage progress = wire::decode<wire::ProgressMessage>(message);
  const auto dropped = dropped_.find(progress.frame);
  if (dropped != dropped_.end()) progress.jobsReceived += dropped->second;
  for (const HeldResult& h : held_) {
    if (h.frame == progress.frame) progress.heldTiles.push_back(h.tile);
  }
  std::sort(progress.heldTiles.begin(), progress.heldTiles.end());
  progress.heldTiles.erase(std::unique(progress.heldTiles.begin(), progress.heldTiles.end()),
                           progress.heldTiles.end());
  return wire::encode(progress);
}

// The result takes the render thread's lane that is free first, for kSlowTileDelaySeconds from
// the later of now and then. Due times never decrease, so the queue stays in release order.
void FaultInjectingTransport::holdBack(int dest, const wire::Message& message,
                                       std::vector<uint8_t>&& bytes) {
  const wire::TileResultMessage result = wire::decode<wire::TileResultMessage>(message);
  double& lane = *std::min_element(lanes_.begin(), lanes_.end());
  lane = std::max(clock_(), lane) + kSlowTileDelaySeconds;
  held_.push_back({lane, dest, result.frame, result.result.tileIndex, std::move(bytes)});
}

void FaultInjectingTransport::releaseDue() {
  const double now = clock_();
  while (!held_.empty() && held_.front().due <= now) {
    if (!inner_.send(held_.front().dest, std::move(held_.front().bytes))) releaseFailed_ = true;
    held_.pop_front();
  }
}

double FaultInjectingTransport::secondsUntilDue() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (held_.empty()) return 1e9;
  return std::max(0.0, held_.front().due - clock_());
}

}  // namespace prism

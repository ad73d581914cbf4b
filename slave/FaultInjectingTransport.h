// A Transport that makes its rank misbehave as a FaultInjection says (--inject-fault), around
// any other Transport (MPI or loopback): the slave's own code knows nothing of faults, and what
// each kind does is a statement about the messages the rank sends and receives (the exact
// semantics are in common/cluster/FaultInjection.h). Lives in slave/, not in common/: it reads
// the wire format, and the transport layer sits below it.
//
// Threads: like the transport it wraps, send, poll and waitForMessage are called by one thread
// at a time; awaitActivity and wake may run beside them.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <vector>

#include "cluster/FaultInjection.h"
#include "transport/Transport.h"
#include "wire/Messages.h"

namespace prism {

class FaultInjectingTransport final : public Transport {
 public:
  // Seconds on a steady clock, for a slow rank's timing; tests pass their own.
  using Clock = std::function<double()>;

  FaultInjectingTransport(Transport& inner, FaultInjection::Kind kind, Clock clock = {});

  int rank() const override { return inner_.rank(); }
  int size() const override { return inner_.size(); }
  double setUpSeconds() const override { return inner_.setUpSeconds(); }
  int ranksOnThisNode() const override { return inner_.ranksOnThisNode(); }
  void broadcast(std::vector<uint8_t>& bytes, double timeoutSeconds) override {
    inner_.broadcast(bytes, timeoutSeconds);
  }

  // Swallowed and held-back messages count as sent (true); false when the inner transport
  // refused this one, or a held-back result released since the last send.
  bool send(int dest, std::vector<uint8_t> bytes) override;
  size_t progressSends() override;
  std::optional<IncomingMessage> poll() override;
  std::optional<IncomingMessage> waitForMessage(double timeoutSeconds) override;
  // Returns by the time the next held-back result is due, so the caller's next call sends it.
  void awaitActivity(double timeoutSeconds) override;
  void wake() override { inner_.wake(); }
  bool wakesOnMessage() const override { return inner_.wakesOnMessage(); }
  [[noreturn]] void abortJob(int exitCode) override;

  // Slow: the tile results held back, not yet sent.
  size_t heldBack() const;

 private:
  struct HeldResult {
    double due = 0.0;
    int dest = 0;
    uint32_t frame = 0;
    uint32_t tile = 0;
    std::vector<uint8_t> bytes;
  };

  // Whether an incoming message reaches the rank; ends the process for the crash kinds.
  bool admit(const std::vector<uint8_t>& bytes);
  // The first message of `incoming` and what is queued after it that reaches the rank.
  std::optional<IncomingMessage> firstAdmitted(std::optional<IncomingMessage> incoming);
  // What to send for `bytes`: the same, rewritten (Progress), or nothing (swallowed, or held
  // back: then it is queued).
  std::optional<std::vector<uint8_t>> outgoing(int dest, std::vector<uint8_t>&& bytes);
  std::vector<uint8_t> rewriteProgress(const wire::Message& message) const;
  void holdBack(int dest, const wire::Message& message, std::vector<uint8_t>&& bytes);
  void releaseDue();
  double secondsUntilDue() const;

  Transport& inner_;
  const FaultInjection::Kind kind_;
  const Clock clock_;
  mutable std::mutex mutex_;
  std::map<uint32_t, uint64_t> tileJobs_;  // drop: TileJobs that came, by frame
  std::map<uint32_t, uint64_t> dropped_;   // drop: of those, swallowed
  std::deque<HeldResult> held_;            // slow: in order of release
  std::vector<double> lanes_{0.0};         // slow: when each render thread is next free
  bool releaseFailed_ = false;
};

}  // namespace prism

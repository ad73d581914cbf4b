// Every rank of a job as a thread of one process: a Transport per rank over shared mailboxes.
// The master–slave protocol runs over it unchanged, so its tests need no mpiexec, run in
// milliseconds, and can script a misbehaving rank message by message (late, duplicate, lost,
// out-of-order messages; a rank that vanishes).
#pragma once

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <vector>

#include "transport/Transport.h"

namespace prism {

class LoopbackNetwork {
 public:
  explicit LoopbackNetwork(int ranks);
  ~LoopbackNetwork();
  LoopbackNetwork(const LoopbackNetwork&) = delete;
  LoopbackNetwork& operator=(const LoopbackNetwork&) = delete;

  int size() const { return static_cast<int>(endpoints_.size()); }
  // Rank r's view of the job; lives as long as the network.
  Transport& endpoint(int rank);

  // The rank is gone, as a killed process is to `mpirun --enable-recovery`: sends to and from
  // it fail from now on, and what was queued for it is dropped.
  void disconnect(int rank);
  bool connected(int rank);

  // How many messages have been sent to a rank so far (tests wait on it).
  size_t deliveredTo(int rank);

 private:
  class Endpoint;
  friend class Endpoint;
  struct Mailbox {
    std::deque<IncomingMessage> messages;
    size_t delivered = 0;
    bool connected = true;
    bool woken = false;  // wake() since the rank last waited
  };

  bool deliver(int source, int dest, std::vector<uint8_t> bytes);
  std::optional<IncomingMessage> take(int rank, double timeoutSeconds);
  void await(int rank, double timeoutSeconds);
  void wake(int rank);

  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<Mailbox> mailboxes_;
  std::vector<std::vector<uint8_t>> broadcasts_;  // in order; every rank takes each once
  std::vector<std::unique_ptr<Endpoint>> endpoints_;
};

}  // namespace prism

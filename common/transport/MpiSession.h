// The transport over MPI, and the only code in Prism that talks to MPI (common/transport/
// Transport.h says what a transport does). Built into the module prism_mpi.so, which a process
// loads only when an MPI launcher started it (transport/MpiModule.h).
#pragma once

#include <list>
#include <memory>
#include <string>
#include <vector>

#include "transport/Doorbell.h"
#include "transport/Transport.h"

namespace prism {

class MpiSession final : public Transport {
 public:
  // Initialises MPI (threads allowed; MPI called from one thread at a time: the main thread,
  // or in `prism view` the master's coordinator thread).
  MpiSession(int* argc, char*** argv);
  ~MpiSession();  // waits a bounded time for outstanding sends, then finalises
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  double setUpSeconds() const override { return initSeconds_; }
  int ranksOnThisNode() const override;

  // Rank 0's bytes reach every rank. Throws TransportError after timeoutSeconds.
  void broadcast(std::vector<uint8_t>& bytes, double timeoutSeconds) override;

  // Queues bytes for rank dest without blocking; the buffer lives until the send completes.
  // Returns false when MPI refuses at once (the destination is known to be gone, e.g. under
  // `mpirun --enable-recovery`) or a destination on this machine no longer answers its doorbell
  // (its process has ended); the caller decides what that rank's loss means.
  bool send(int dest, std::vector<uint8_t> bytes) override;
  // Completes finished sends; returns how many are still outstanding.
  size_t progressSends() override;

  // A message from any rank, if one has arrived.
  std::optional<IncomingMessage> poll() override;
  // Waits up to timeoutSeconds for a message from any rank, or until wake().
  std::optional<IncomingMessage> waitForMessage(double timeoutSeconds) override;
  // Sleeps until a peer rings this rank's doorbell or 1 ms passes (then the caller probes).
  void awaitActivity(double timeoutSeconds) override;
  void wake() override;
  bool wakesOnMessage() const override { return rungByPeers_; }

  // Ends every process of the job (MPI_Abort) after the caller has printed why.
  [[noreturn]] void abortJob(int exitCode) override;

 private:
  struct PendingSend;
  void setUpDoorbells();
  void finalizeBounded();
  // Rings dest's doorbell where it has one; false if that bell is gone (so is its process).
  bool ring(int dest) const;
  Doorbell::Heard sleepFor(double seconds);

  int rank_ = 0;
  int size_ = 1;
  double initSeconds_ = 0.0;  // MPI_Init_thread
  std::list<std::unique_ptr<PendingSend>> pendingSends_;
  std::unique_ptr<Doorbell> doorbell_;
  std::vector<std::string> peerDoorbells_;  // by rank; empty for ranks on other machines
  bool rungByPeers_ = false;                // every rank this one waits for can ring it
};

}  // namespace prism

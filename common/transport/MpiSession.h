// The only code in Prism that talks to MPI: process start and end, the scene broadcast, and
// point-to-point messages as opaque byte strings (their format is common/wire). master/ and
// slave/ use it; the renderer core never does. Every wait here is bounded.
#pragma once

#include <cstdint>
#include <list>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace prism {

// Whether this process was started by an MPI launcher (mpirun, mpiexec, srun). Without one,
// Prism runs as a single process and never initialises MPI.
bool launchedByMpiLauncher();

class TransportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct IncomingMessage {
  int source = 0;
  std::vector<uint8_t> bytes;
};

class MpiSession {
 public:
  // Initialises MPI (threads allowed; MPI called from one thread at a time: the main thread,
  // or in `prism view` the master's coordinator thread).
  MpiSession(int* argc, char*** argv);
  ~MpiSession();  // waits a bounded time for outstanding sends, then finalises
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }

  // Rank 0's bytes reach every rank. Throws TransportError after timeoutSeconds.
  void broadcast(std::vector<uint8_t>& bytes, double timeoutSeconds);

  // Queues bytes for rank dest without blocking; the buffer lives until the send completes.
  // Returns false when MPI refuses at once (the destination is known to be gone, e.g. under
  // `mpirun --enable-recovery`); the caller decides what that rank's loss means.
  bool send(int dest, std::vector<uint8_t> bytes);
  // Completes finished sends; returns how many are still outstanding.
  size_t progressSends();

  // A message from any rank, if one has arrived.
  std::optional<IncomingMessage> poll();
  // Waits up to timeoutSeconds for a message from any rank.
  std::optional<IncomingMessage> waitForMessage(double timeoutSeconds);

  // Ends every process of the job (MPI_Abort) after the caller has printed why.
  [[noreturn]] void abortJob(int exitCode);

 private:
  struct PendingSend;
  int rank_ = 0;
  int size_ = 1;
  std::list<std::unique_ptr<PendingSend>> pendingSends_;
};

}  // namespace prism

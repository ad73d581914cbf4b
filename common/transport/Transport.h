// How ranks talk: process identity, the scene broadcast, and point-to-point messages as opaque
// byte strings (their format is common/wire). Two implementations: MpiSession (the only code
// that links MPI) and LoopbackTransport (every rank a thread of one process, so the
// master–slave protocol is tested without mpiexec). master/ and slave/ see only this interface;
// the renderer core never does. Every wait here is bounded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

namespace prism {

class TransportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct IncomingMessage {
  int source = 0;
  std::vector<uint8_t> bytes;
};

class Transport {
 public:
  virtual ~Transport() = default;

  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Seconds this process spent setting the transport up (MPI_Init), for `prism speedup`.
  virtual double setUpSeconds() const { return 0.0; }
  // The job's ranks on this rank's machine, itself included (1 when the launcher does not say):
  // ranks there share its cores, which decides whether building the scene on every rank pays.
  virtual int ranksOnThisNode() const { return 1; }

  // Rank 0's bytes reach every rank. Throws TransportError after timeoutSeconds.
  virtual void broadcast(std::vector<uint8_t>& bytes, double timeoutSeconds) = 0;

  // Queues bytes for rank dest without blocking; the buffer lives until the send completes.
  // Returns false when the transport refuses at once (the destination is known to be gone,
  // e.g. under `mpirun --enable-recovery`); the caller decides what that rank's loss means.
  virtual bool send(int dest, std::vector<uint8_t> bytes) = 0;
  // Completes finished sends; returns how many are still outstanding.
  virtual size_t progressSends() = 0;

  // A message from any rank, if one has arrived.
  virtual std::optional<IncomingMessage> poll() = 0;
  // Waits up to timeoutSeconds for a message from any rank; returns early, with none, after
  // wake().
  virtual std::optional<IncomingMessage> waitForMessage(double timeoutSeconds) = 0;

  // Sleeps until a message may have arrived (poll() tells), wake() is called, or timeoutSeconds
  // pass; it may return early (MpiSession: after at most 1 ms, for a probe). Calls nothing that
  // must be serialised, so another thread may use the transport meanwhile (a slave's
  // heartbeat).
  virtual void awaitActivity(double timeoutSeconds) = 0;
  // Ends a waitForMessage() or awaitActivity() in progress, or the next one, at once. Safe from
  // any thread: how local events (a finished tile, a stop) reach a thread waiting for messages.
  virtual void wake() = 0;
  // Whether a sender's message ends this rank's wait at once (rather than at the next probe).
  virtual bool wakesOnMessage() const = 0;

  // Ends every process of the job after the caller has printed why.
  [[noreturn]] virtual void abortJob(int exitCode) = 0;
};

}  // namespace prism

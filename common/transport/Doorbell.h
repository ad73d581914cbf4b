// A wake-up call between processes on one machine, so a rank waiting for a message sleeps until
// one is sent instead of probing MPI every millisecond. Open MPI has no waiting primitive that
// sleeps (its blocking calls spin on the core a render thread needs), so each rank binds a
// Unix datagram socket in Linux's abstract namespace; a sender rings the receiver's bell (one
// byte) after posting its message, and the receiver sleeps in poll() on its own bell. The bell
// carries no data: whoever wakes still asks MPI what arrived. Plain sockets, no MPI.
#pragma once

#include <string>

namespace prism {

class Doorbell {
 public:
  // Binds this process's bell as `name` (unique on the machine) for peers to ring. Without a
  // name, or where binding fails (no abstract namespace), only this process can ring it:
  // reachable() says which.
  explicit Doorbell(const std::string& name = {});
  ~Doorbell();
  Doorbell(const Doorbell&) = delete;
  Doorbell& operator=(const Doorbell&) = delete;

  bool reachable() const { return bound_; }

  // Rings the bell a peer bound as `name`; false only if nobody has (the peer's process is
  // gone: a bound bell lives as long as its process). A bell with rings not yet heard is not
  // rung twice (the socket's queue is full): one wake-up is enough. Safe from any thread, like
  // ringSelf().
  bool ring(const std::string& name) const;
  // Ends this process's wait() in progress, or the next one, at once.
  void ringSelf() const;

  enum class Heard { Nothing, Peer, Self };
  // Sleeps until the bell rings or `seconds` pass, and hears every ring so far: Self if this
  // process rang (whatever else did), Peer if only peers did.
  Heard wait(double seconds);

 private:
  int socket_ = -1;               // bound as the name, when bound_
  int selfSocket_[2] = {-1, -1};  // a connected pair for ringSelf(), always there
  bool bound_ = false;
};

}  // namespace prism

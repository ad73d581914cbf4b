// A slave's heartbeat: a thread that sends rank 0 the frame book's Progress (jobs received,
// tiles held, per running frame) every kHeartbeatSeconds. It keeps a slave busy with long tiles
// from being taken for dead, and lets the master spot tiles this rank lost. It shares the
// transport and the frame book with the message loop under one lock (MPI is called from one
// thread at a time); the loop lets go of the lock for anything long, so the heartbeat never
// stops while the rank is alive.
#pragma once

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace prism {

class FrameBook;
class Transport;

class Heartbeat {
 public:
  // Starts beating. `shared` guards the transport and the frames.
  Heartbeat(Transport& transport, std::mutex& shared, const FrameBook& frames);
  ~Heartbeat();  // stops
  Heartbeat(const Heartbeat&) = delete;
  Heartbeat& operator=(const Heartbeat&) = delete;

  // Stops the thread (idempotent). Call without holding `shared`.
  void stop();
  // Whether a beat could not be sent: rank 0 is gone.
  bool masterGone() const { return masterGone_; }

 private:
  void beat();

  Transport& transport_;
  std::mutex& shared_;
  const FrameBook& frames_;
  std::condition_variable stopped_;
  bool stopping_ = false;  // guarded by shared_
  std::atomic<bool> masterGone_{false};
  std::thread thread_;
};

}  // namespace prism

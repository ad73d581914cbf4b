// Wakes a poll loop from another thread: a byte into a pipe the loop watches, 'u' when what
// woke it is urgent. Non-blocking both ways: a full pipe means a wake is pending already.
#pragma once

namespace prism {

class WakePipe {
 public:
  WakePipe();  // throws std::runtime_error
  ~WakePipe();
  WakePipe(const WakePipe&) = delete;
  WakePipe& operator=(const WakePipe&) = delete;

  void wake(bool urgent);

  struct Woken {
    bool any = false;
    bool urgent = false;
  };
  // Empties the pipe; says whether anything, and anything urgent, was in it.
  Woken drain();
  // The end to poll for reading.
  int fd() const { return fds_[0]; }

 private:
  int fds_[2];
};

}  // namespace prism

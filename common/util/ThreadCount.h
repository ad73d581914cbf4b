// The threads a rank works with, decided once where the rank starts (rank 0's WorkDispatcher, a
// slave's SlaveSession) and passed down from there: the command line's --threads, or every core
// available to the rank when it names none. resolve() is the one place a thread count is given
// that default; a ThreadCount is never 0.
#pragma once

#include "util/Parallel.h"

namespace prism {

class ThreadCount {
 public:
  // requested ≤ 0: every core available to this process (availableCores()).
  static ThreadCount resolve(int requested) {
    return ThreadCount(requested > 0 ? requested : availableCores());
  }
  int value() const { return value_; }

 private:
  explicit ThreadCount(int value) : value_(value) {}
  int value_;
};

}  // namespace prism

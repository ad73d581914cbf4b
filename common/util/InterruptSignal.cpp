#include "util/InterruptSignal.h"

#include <atomic>
#include <csignal>

namespace prism {
namespace {

// Lock-free, so storing from a signal handler is async-signal-safe.
std::atomic<int> receivedSignal{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void onInterrupt(int signal) {
  int expected = 0;
  if (!receivedSignal.compare_exchange_strong(expected, signal)) {
    // The second Ctrl-C: the user does not want to wait. Default action, now.
    std::signal(signal, SIG_DFL);
    std::raise(signal);
  }
}

}  // namespace

void installInterruptHandlers() {
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // the MPI progress engine and file writes carry on
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool interruptRequested() {
  return receivedSignal.load(std::memory_order_relaxed) != 0;
}

const char* interruptSignalName() {
  switch (receivedSignal.load()) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "";
  }
}

void clearInterruptForTesting() {
  receivedSignal.store(0);
}

}  // namespace prism

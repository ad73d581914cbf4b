// A test that waits for an event (a retired slave, a woken wait, a finished frame) must not judge
// how fast it came: a sanitizer build or a loaded machine is slow, not broken. It only needs to
// fail, rather than hang, when the event never comes. unlessItHangs runs the work on a thread of
// its own and returns its result; if the work has not returned after kHangSeconds, the event is
// taken to be missing: the test fails and the binary exits, since the hung thread cannot be
// joined. Every timeout the code under test could fall back on must lie beyond kHangSeconds (a
// lease of kNeverSeconds), so that reaching the guard means the awaited event did not happen.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <future>
#include <memory>
#include <thread>
#include <type_traits>

namespace prism::test {

inline constexpr double kHangSeconds = 60.0;
// A timeout that never runs out within a test: leases and silences the code must not wait for.
inline constexpr double kNeverSeconds = 3600.0;

template <typename Work>
auto unlessItHangs(Work work, double seconds = kHangSeconds) -> decltype(work()) {
  using Result = decltype(work());
  auto promise = std::make_shared<std::promise<Result>>();
  std::future<Result> result = promise->get_future();
  std::thread([promise, work]() mutable {
    try {
      if constexpr (std::is_void_v<Result>) {
        work();
        promise->set_value();
      } else {
        promise->set_value(work());
      }
    } catch (...) {
      promise->set_exception(std::current_exception());
    }
  }).detach();
  if (result.wait_for(std::chrono::duration<double>(seconds)) == std::future_status::timeout) {
    ADD_FAILURE() << "still waiting after " << seconds << " s: the awaited event never came";
    std::fflush(stdout);
    std::_Exit(1);
  }
  return result.get();
}

}  // namespace prism::test

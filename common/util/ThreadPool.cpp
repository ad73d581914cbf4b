#include "util/ThreadPool.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <system_error>

namespace prism {

// One run() call: its indices, and the pool threads that help with it.
struct ThreadPool::Loop {
  Loop(const std::function<void(uint64_t)>& b, uint64_t n, size_t helpers)
      : body(b), count(n), helpersWanted(helpers) {}

  // Takes indices until none is left; a call that throws ends the handing out.
  void work() {
    for (uint64_t i = next++; i < count; i = next++) {
      try {
        body(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failureMutex);
        if (!failure) failure = std::current_exception();
        next = count;
      }
    }
  }

  const std::function<void(uint64_t)>& body;
  const uint64_t count;
  std::atomic<uint64_t> next{0};
  // Under the pool's mutex:
  size_t helpersWanted;  // places left for pool threads
  size_t helping = 0;    // pool threads in the loop now
  std::condition_variable helpersLeft;
  std::mutex failureMutex;
  std::exception_ptr failure;
};

ThreadPool::~ThreadPool() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  work_.notify_all();
  for (std::thread& t : threads_) t.join();
}

ThreadPool& ThreadPool::shared() {
  // Never destroyed: its idle threads wait until the process exits, and a static destructor
  // that still runs a loop finds the pool there.
  static ThreadPool* const pool = new ThreadPool();
  return *pool;
}

size_t ThreadPool::threadCount() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return threads_.size();
}

void ThreadPool::run(uint64_t count, int threads, const std::function<void(uint64_t)>& body) {
  const uint64_t n =
      std::min<uint64_t>(static_cast<uint64_t>(std::max(threads, 1)), std::max<uint64_t>(count, 1));
  if (n == 1) {
    for (uint64_t i = 0; i < count; ++i) body(i);
    return;
  }
  Loop loop(body, count, n - 1);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    waiting_.push_back(&loop);
    // As many threads as the loops waiting want: new ones where too few are idle.
    size_t wanted = 0;
    for (const Loop* l : waiting_) wanted += l->helpersWanted;
    while (idle_ < wanted) {
      try {
        threads_.emplace_back([this] { serve(); });
      } catch (const std::system_error&) {
        break;  // none to be had: the threads there (and this one) take every index
      }
      ++idle_;
    }
  }
  for (uint64_t h = 1; h < n; ++h) work_.notify_one();
  loop.work();
  {
    // No thread joins it any more; those in it finish their last index.
    std::unique_lock<std::mutex> lock(mutex_);
    const auto it = std::find(waiting_.begin(), waiting_.end(), &loop);
    if (it != waiting_.end()) waiting_.erase(it);
    loop.helpersLeft.wait(lock, [&loop] { return loop.helping == 0; });
  }
  if (loop.failure) std::rethrow_exception(loop.failure);
}

void ThreadPool::serve() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    work_.wait(lock, [this] { return stopping_ || !waiting_.empty(); });
    if (stopping_) return;
    Loop& loop = *waiting_.front();
    if (--loop.helpersWanted == 0) waiting_.pop_front();
    ++loop.helping;
    --idle_;
    lock.unlock();
    loop.work();
    lock.lock();
    ++idle_;
    // The loop's caller may return (and the loop go) once the lock is released.
    if (--loop.helping == 0) loop.helpersLeft.notify_all();
  }
}

}  // namespace prism

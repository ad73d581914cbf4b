// Threads kept for parallel loops (parallelFor, forChunks): started when a loop first needs
// them and reused by every loop after, instead of started and joined for each one. A loop runs
// on the calling thread and on idle pool threads; the pool grows when more loops run at once
// (nested ones too: a BVH build's halves each start loops of their own) than it has idle
// threads, so a loop gets the threads it asks for, as it would with threads of its own.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace prism {

class ThreadPool {
 public:
  ThreadPool() = default;
  ~ThreadPool();  // waits for its threads, which are idle once no loop runs
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  // The process's pool, which parallelFor uses: kept until the process exits.
  static ThreadPool& shared();

  // Calls body(i) once for each i in [0, count) on up to `threads` threads (≥ 1), the calling
  // thread among them, and returns when all are done. Indices are handed out one at a time in
  // increasing order. The first exception a call throws stops the handing out and is rethrown
  // here once the threads have left the loop.
  void run(uint64_t count, int threads, const std::function<void(uint64_t)>& body);

  // Threads started so far.
  size_t threadCount();

 private:
  struct Loop;
  void serve();

  std::mutex mutex_;
  std::condition_variable work_;      // a loop wants helpers, or the pool stops
  std::deque<Loop*> waiting_;         // loops that want more helpers, oldest first
  std::vector<std::thread> threads_;  // every thread started; each idle or helping a loop
  size_t idle_ = 0;                   // threads waiting for a loop (or about to)
  bool stopping_ = false;
};

}  // namespace prism

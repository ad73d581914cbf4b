#include "slave/TileWorkerPool.h"

#include <sched.h>

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include "render/TileRenderer.h"

namespace prism {

int availableCores() {
  // The affinity mask respects taskset, cgroups' cpusets and mpirun's binding.
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0) {
    const int count = CPU_COUNT(&set);
    if (count > 0) return count;
  }
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware > 0 ? static_cast<int>(hardware) : 1;
}

TileWorkerPool::TileWorkerPool(const Scene& scene, int threadCount)
    : scene_(scene), threadCount_(threadCount > 0 ? threadCount : availableCores()) {}

void TileWorkerPool::renderAll(const std::vector<TileJob>& jobs, const ResultHandler& onResult,
                               const std::function<void()>& onIdle, int pollMilliseconds) const {
  const TileRenderer renderer(scene_);
  std::atomic<size_t> next{0};
  std::mutex resultMutex;
  std::mutex doneMutex;
  std::condition_variable doneSignal;
  int running = threadCount_;
  std::exception_ptr failure;

  auto work = [&] {
    try {
      for (size_t i = next++; i < jobs.size(); i = next++) {
        TileResult result = renderer.render(jobs[i].tileIndex, jobs[i].rect);
        const std::lock_guard<std::mutex> lock(resultMutex);
        onResult(std::move(result));
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(resultMutex);
      if (!failure) failure = std::current_exception();
      next = jobs.size();  // let the other threads stop early
    }
    const std::lock_guard<std::mutex> lock(doneMutex);
    --running;
    doneSignal.notify_all();
  };

  std::vector<std::thread> threads;
  threads.reserve(static_cast<size_t>(threadCount_));
  for (int t = 0; t < threadCount_; ++t) threads.emplace_back(work);
  {
    std::unique_lock<std::mutex> lock(doneMutex);
    while (running > 0) {
      doneSignal.wait_for(lock, std::chrono::milliseconds(pollMilliseconds));
      if (onIdle && running > 0) {
        lock.unlock();
        onIdle();
        lock.lock();
      }
    }
  }
  for (std::thread& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace prism

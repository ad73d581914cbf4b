#include "util/Parallel.h"

#include <sched.h>

#include <thread>

#include "util/ThreadCount.h"
#include "util/ThreadPool.h"

namespace prism {

int availableCores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0) {
    const int count = CPU_COUNT(&set);
    if (count > 0) return count;
  }
  return machineCores();
}

int machineCores() {
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware > 0 ? static_cast<int>(hardware) : 1;
}

void parallelFor(uint64_t count, int threads, const std::function<void(uint64_t)>& body) {
  ThreadPool::shared().run(count, ThreadCount::resolve(threads).value(), body);
}

}  // namespace prism

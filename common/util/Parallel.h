// The machine's parallelism as this process sees it, and the one parallel loop the core uses.
#pragma once

#include <cstdint>
#include <functional>

namespace prism {

// The cores this process may run on: its CPU affinity mask (taskset, cgroup cpusets, mpirun's
// --bind-to), not the machine's thread count, so a bound rank does not oversubscribe its cores.
int availableCores();

// The machine's hardware threads, whatever this process is bound to: what `prism speedup` compares
// ranks × threads with to label a point oversubscribed (rank 0 is often bound to one core).
int machineCores();

// Calls body(i) once for each i in [0, count) on up to `threads` threads (0: availableCores()):
// the caller and threads of the process's pool (util/ThreadPool.h). Returns when all are done,
// rethrowing a call's exception. Indices go out one at a time in increasing order, so uneven
// items balance; results must not depend on which thread runs an index (item i to slot i).
void parallelFor(uint64_t count, int threads, const std::function<void(uint64_t)>& body);

// body(begin, end) over [0, count) in chunks of `chunk`, on up to `threads` threads, for items
// too small to hand out one at a time. Every item has its own slot, so the result is the same
// for any number of threads.
inline void forChunks(uint64_t count, uint64_t chunk, unsigned threads,
                      const std::function<void(uint64_t, uint64_t)>& body) {
  parallelFor((count + chunk - 1) / chunk, static_cast<int>(threads), [&](uint64_t c) {
    body(c * chunk, count < (c + 1) * chunk ? count : (c + 1) * chunk);
  });
}

}  // namespace prism

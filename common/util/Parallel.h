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

// Calls body(i) once for each i in [0, count), on up to `threads` threads (0: availableCores()),
// the calling thread among them, and returns when all are done. Indices are handed out one at a
// time in increasing order, so uneven items balance; results must not depend on which thread
// runs an index (callers write item i to slot i).
void parallelFor(uint64_t count, int threads, const std::function<void(uint64_t)>& body);

}  // namespace prism

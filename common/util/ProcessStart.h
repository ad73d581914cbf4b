// When this process started, for `prism speedup`'s account of what a job spends before its
// first frame: the launcher's share (from the parent's start, which under mpirun on one node is
// mpirun itself) and the process's own (loading libraries, MPI_Init). Linux /proc, in clock ticks
// (10 ms); nullopt where /proc cannot be read.
#pragma once

#include <optional>

namespace prism {

// Seconds from this process's start to now.
std::optional<double> secondsSinceProcessStart();

// Seconds from the parent process's start to this one's.
std::optional<double> secondsFromParentStart();

}  // namespace prism

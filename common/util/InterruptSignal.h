// Ctrl-C during a render. SIGINT (a terminal's Ctrl-C, or `kill -INT`) and SIGTERM (what
// Open MPI's mpiexec sends every rank about a second after it receives SIGINT itself, with
// SIGKILL a second later) only raise a flag here. Rank 0's frame loop polls it, stops handing
// out tiles and writes what it has (--save-partial); a slave polls it too, stops rendering and
// waits briefly for rank 0's shutdown, so that it does not die under rank 0 while rank 0
// writes (mpiexec kills the whole job at once when one rank dies).
#pragma once

namespace prism {

// Installs the handlers on this process. A second signal while the first is being handled
// ends the process at once, as Ctrl-C would without them.
void installInterruptHandlers();

// Whether SIGINT or SIGTERM arrived since the handlers were installed.
bool interruptRequested();

// The signal's name ("SIGINT", "SIGTERM"), or "" when none arrived.
const char* interruptSignalName();

// The exit status of an interrupted run, 128 + SIGINT, as shells report Ctrl-C.
inline constexpr int kInterruptedExitCode = 130;

// Tests: forgets a received signal.
void clearInterruptForTesting();

}  // namespace prism

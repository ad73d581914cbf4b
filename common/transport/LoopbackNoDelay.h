// Open MPI's ranks talk to their launcher's PMIx server (mpirun or its daemon on the same
// machine) over TCP on the loopback interface, with Nagle's algorithm on. MPI_Finalize sends the
// server a few small messages in a row: the second waits for the acknowledgement of the first,
// which the server delays by its 40 ms delayed-ACK timer, so every job's end stalled 40 ms
// (strace: the fence request left 42 ms after it was written; docs/distributed.md, "The end of
// a job"). Turning Nagle off on this process's loopback TCP connections removes the stall.
// Plain sockets, no MPI.
#pragma once

namespace prism {

// Sets TCP_NODELAY on every TCP socket of this process connected to a loopback address
// (127.0.0.0/8, ::1, or an IPv4-mapped 127.x); other sockets are left as they are. Returns how
// many it set. Reads the process's descriptors from /proc/self/fd; 0 where that is missing.
int disableNagleOnLoopbackConnections();

}  // namespace prism

// The end of an MPI job. Each slave answers rank 0's Shutdown with its own Shutdown as it leaves.
// One that does not answer within the bound is stopped or wedged, and one the transport knows
// has ended (a crash under --enable-recovery) is dead; MPI_Finalize would wait for either
// forever, so the job is ended with MPI_Abort instead, after saying why. The image is
// already written by then, and the exit code stays the run's own.
#pragma once

#include <iosfwd>
#include <vector>

namespace prism {

class Transport;

// Returns exitCode when every slave acknowledged (or session is null or has no slaves); does
// not return otherwise. Slaves marked silent (retired during the frame) get a shorter wait.
int shutDownSlaves(Transport* session, int exitCode, const std::vector<bool>& silent,
                   std::ostream& err);

// The end of a job mpiexec is already tearing down (rank 0 got SIGTERM, and SIGKILL follows in
// a second): tells the slaves to stop, gives the messages a moment to leave, and exits with
// exitCode without MPI_Finalize, which would wait for a job that is going away.
[[noreturn]] void leaveEndingJob(Transport& session, int exitCode);

}  // namespace prism

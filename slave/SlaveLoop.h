// What ranks other than 0 do: receive the scene, build it, render the tiles the master sends
// with their threads, send the results back, and stop when told.
#pragma once

#include "cluster/DistributionOptions.h"

namespace prism {

class Transport;

// Returns the process exit code. Errors are sent to the master, which reports them; a slave
// prints only when it cannot reach the master.
// Reads options.threads, masterTimeoutSeconds and fault.
int runSlave(Transport& session, const DistributionOptions& options);

}  // namespace prism

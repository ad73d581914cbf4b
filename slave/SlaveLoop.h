// What ranks other than 0 do: receive the scene, build it, render the tiles the master sends
// with their threads, send the results back, and stop when told.
#pragma once

#include "cluster/DistributionOptions.h"
#include "util/MemorySize.h"

namespace prism {

class Transport;

struct SlaveEnd {
  int exitCode = 0;
  // Rank 0 is gone (a send to it failed) or silent past masterTimeoutSeconds: the process should
  // end without MPI_Finalize, which waits for every rank, rank 0 included.
  bool masterLost = false;
};

// Errors are sent to the master, which reports them; a slave prints only when it cannot reach
// the master.
// Reads options.threads, masterTimeoutSeconds and fault (when it names this rank, the session
// talks through a FaultInjectingTransport around `session`). A scene whose geometry exceeds
// memoryLimit (this rank's --memory-limit, or its machine's memory) is refused before it is built.
SlaveEnd runSlave(Transport& session, const DistributionOptions& options,
                  const MemoryLimit& memoryLimit = {});

}  // namespace prism

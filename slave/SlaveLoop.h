// What ranks other than 0 do: receive the scene, build it, render the tiles the master sends
// with their threads, send the results back, and stop when told.
#pragma once

#include "slave/FaultInjection.h"

namespace prism {

class MpiSession;

struct SlaveOptions {
  int threads = 0;                      // 0: every core available to this rank
  double masterTimeoutSeconds = 600.0;  // give up when the master has been silent this long
  FaultInjection fault;
};

// Returns the process exit code. Errors are sent to the master, which reports them; a slave
// prints only when it cannot reach the master.
int runSlave(MpiSession& session, const SlaveOptions& options);

}  // namespace prism

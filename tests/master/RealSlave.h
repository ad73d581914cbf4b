// A real slave (runSlave, one render thread) on a thread of its own over the loopback, for tests
// of rank 0 against the slave's actual loop.
#pragma once

#include <thread>

#include "cluster/DistributionOptions.h"
#include "slave/SlaveLoop.h"
#include "transport/LoopbackTransport.h"

namespace prism::test {

// Runs rank `rank` of `network` until it ends; its exit code lands in *exitCode (join first).
// memoryLimit: the slave's own (--memory-limit on that rank).
inline std::thread startRealSlave(LoopbackNetwork& network, int rank, int* exitCode,
                                  MemoryLimit memoryLimit = {}) {
  return std::thread([&network, rank, exitCode, memoryLimit] {
    DistributionOptions options;
    options.threads = 1;
    options.masterTimeoutSeconds = 30.0;
    *exitCode = runSlave(network.endpoint(rank), options, memoryLimit).exitCode;
  });
}

}  // namespace prism::test

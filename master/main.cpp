// prism: the one executable, and the composition root: the only place that decides a process's
// role. Subcommands are described by `prism` alone and `prism --help`. Started by an MPI
// launcher, every rank runs this: rank 0 becomes the master and runs the command, the others
// slaves, whatever the command. MPI and Qt are modules loaded only when used (MpiModule.h,
// ViewerModule.h), so a process pays at start-up only for the libraries it needs.
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>

#include "master/commands/Cli.h"
#include "math/Simd.h"
#include "slave/SlaveLoop.h"
#include "transport/MpiModule.h"
#include "util/PhysicalMemory.h"
#ifdef PRISM_HAVE_VIEWER
#include "gui/ViewerModule.h"
#endif

int main(int argc, char** argv) {
  if (!prism::simd::cpuRunsThisBuild()) {
    std::cerr << "prism: error: this build assumes " << prism::simd::compiledInstructionSet()
              << " instructions, which this CPU lacks; rebuild without -DPRISM_ARCH or with a "
                 "lower level (docs/performance.md)\n";
    return 1;
  }
  std::unique_ptr<prism::Transport> session;
  if (prism::launchedByMpiLauncher()) {
    try {
      session = prism::openMpiTransport(&argc, &argv);
    } catch (const std::exception& e) {
      std::cerr << "prism: error: " << e.what() << "\n";
      return 1;
    }
  }
  const bool slave = session && session->rank() != 0;
#ifdef PRISM_HAVE_VIEWER
  const prism::ParsedCommand command = prism::parseCommandLine(
      argc, argv, slave, prism::lazyViewerRunner(), prism::lazyChartWriter());
#else
  const prism::ParsedCommand command = prism::parseCommandLine(argc, argv, slave);
#endif
  if (command.exitNow) return command.exitCode;
  if (slave) {
    const prism::SlaveEnd end = prism::runSlave(*session, command.distribution,
                                                prism::memoryLimitOrPhysical(command.memoryLimit));
    // Without rank 0, MPI_Finalize (in the session's destructor) would wait for it forever.
    if (end.masterLost) {
      std::fflush(nullptr);
      std::_Exit(end.exitCode);
    }
    return end.exitCode;
  }
  return command.runMaster(session.get());
}

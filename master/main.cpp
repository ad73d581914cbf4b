// prism: the one executable. Subcommands are described by `prism --help`. Started by an MPI
// launcher, every rank runs this: rank 0 becomes the master, the others slaves.
#include <iostream>
#include <memory>

#include "accel/Simd.h"
#include "master/Cli.h"
#include "transport/MpiSession.h"
#ifdef PRISM_HAVE_VIEWER
#include "gui/ChartImage.h"
#include "gui/Viewer.h"
#endif

int main(int argc, char** argv) {
  if (!prism::simd::cpuRunsThisBuild()) {
    std::cerr << "prism: error: this build assumes " << prism::simd::compiledInstructionSet()
              << " instructions, which this CPU lacks; rebuild without -DPRISM_ARCH or with a "
                 "lower level (docs/performance.md)\n";
    return 1;
  }
  std::unique_ptr<prism::MpiSession> session;
  if (prism::launchedByMpiLauncher()) {
    try {
      session = std::make_unique<prism::MpiSession>(&argc, &argv);
    } catch (const std::exception& e) {
      std::cerr << "prism: error: " << e.what() << "\n";
      return 1;
    }
  }
#ifdef PRISM_HAVE_VIEWER
  return prism::runCli(argc, argv, session.get(), prism::runViewer, prism::writeChartImage);
#else
  return prism::runCli(argc, argv, session.get());
#endif
}

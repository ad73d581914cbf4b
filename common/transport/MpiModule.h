// MPI, loaded only by a process that an MPI launcher started. Linking Open MPI costs every
// process its libraries at start-up (docs/dependencies.md), though a process started without a
// launcher never initialises MPI; so MpiSession lives in a module of its own, prism_mpi.so, that
// main() loads only under mpirun, mpiexec or srun. The module resolves Prism's symbols against the
// executable, which exports them.
#pragma once

#include <memory>
#include <string>

#include "transport/Transport.h"

namespace prism {

// Whether this process was started by an MPI launcher (mpirun, mpiexec, srun). Without one,
// Prism runs as a single process and never loads or initialises MPI.
bool launchedByMpiLauncher();

// What the module exports. kMpiModuleVersion guards against a module of another build.
inline constexpr int kMpiModuleVersion = 1;

struct MpiModuleApi {
  int version;
  // Initialises MPI and returns the transport over it; on failure nullptr and *error says why.
  Transport* (*open)(int* argc, char*** argv, std::string* error);
};

extern "C" {
using MpiModuleEntry = const MpiModuleApi* (*)();
}
inline constexpr const char* kMpiModuleEntryName = "prismMpiModule";

// Loads the module (next to the executable, then where the build put it; $PRISM_MPI_MODULE
// replaces both) and opens the MPI transport. Throws std::runtime_error saying what failed.
std::unique_ptr<Transport> openMpiTransport(int* argc, char*** argv);

}  // namespace prism

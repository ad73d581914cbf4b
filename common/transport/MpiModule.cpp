#include "transport/MpiModule.h"

#include <cstdlib>
#include <stdexcept>

#include "util/PluginModule.h"

#ifndef PRISM_MPI_MODULE_PATH
#define PRISM_MPI_MODULE_PATH ""  // set by the build; without it, only next to the executable
#endif

namespace prism {

bool launchedByMpiLauncher() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(variable) != nullptr) return true;
  }
  return false;
}

std::unique_ptr<Transport> openMpiTransport(int* argc, char*** argv) {
  const PluginModuleSearch search{.fileName = "prism_mpi.so",
                                  .environmentVariable = "PRISM_MPI_MODULE",
                                  .buildPath = PRISM_MPI_MODULE_PATH,
                                  .entryName = kMpiModuleEntryName,
                                  // Open MPI dlopen()s components of its own that expect
                                  // libmpi's symbols in the global scope.
                                  .global = true};
  std::string tried;
  const MpiModuleApi* api = loadPluginApi<MpiModuleApi>(search, kMpiModuleVersion, &tried);
  if (!api) {
    throw std::runtime_error(
        pluginModuleNotFound("started by an MPI launcher, but MPI's module", search, tried, ""));
  }
  std::string error;
  std::unique_ptr<Transport> transport(api->open(argc, argv, &error));
  if (!transport) throw std::runtime_error(error);
  return transport;
}

}  // namespace prism

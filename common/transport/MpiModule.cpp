#include "transport/MpiModule.h"

#include <cstdlib>
#include <stdexcept>

#include "util/PluginModule.h"

namespace prism {

bool launchedByMpiLauncher() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(variable) != nullptr) return true;
  }
  return false;
}

std::unique_ptr<Transport> openMpiTransport(int* argc, char*** argv) {
  PluginModuleSearch search;
  search.fileName = "prism_mpi.so";
  search.environmentVariable = "PRISM_MPI_MODULE";
#ifdef PRISM_MPI_MODULE_PATH
  search.buildPath = PRISM_MPI_MODULE_PATH;
#endif
  search.entryName = kMpiModuleEntryName;
  // Open MPI dlopen()s components of its own that expect libmpi's symbols in the global scope.
  search.global = true;
  const MpiModuleApi* api = nullptr;
  std::string tried;
  loadPluginModule(
      search,
      [&api](void* entry) {
        const MpiModuleApi* candidate = reinterpret_cast<MpiModuleEntry>(entry)();
        if (!candidate || candidate->version != kMpiModuleVersion) return false;
        api = candidate;
        return true;
      },
      &tried);
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

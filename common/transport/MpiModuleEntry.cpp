// The entry point of prism_mpi.so (transport/MpiModule.h): no exception crosses the boundary.
#include <exception>

#include "transport/MpiModule.h"
#include "transport/MpiSession.h"

namespace {

prism::Transport* openMpiSession(int* argc, char*** argv, std::string* error) {
  try {
    return new prism::MpiSession(argc, argv);
  } catch (const std::exception& e) {
    *error = e.what();
    return nullptr;
  }
}

const prism::MpiModuleApi kApi{prism::kMpiModuleVersion, &openMpiSession};

}  // namespace

extern "C" __attribute__((visibility("default"))) const prism::MpiModuleApi* prismMpiModule() {
  return &kApi;
}

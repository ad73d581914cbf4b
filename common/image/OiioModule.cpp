#include "image/OiioModule.h"

#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace prism {
namespace {

namespace fs = std::filesystem;

constexpr const char* kModuleFile = "prism_image_oiio.so";

std::once_flag loadOnce;
std::atomic<const OiioModuleApi*> loaded{nullptr};
std::string loadError;

std::vector<std::string> candidatePaths() {
  // The variable, when set, is the only place: it says where the module is, or that it is not.
  if (const char* env = std::getenv("PRISM_OIIO_MODULE"); env && *env) return {env};
  std::vector<std::string> paths;
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) paths.push_back((exe.parent_path() / kModuleFile).string());
#ifdef PRISM_OIIO_MODULE_PATH
  paths.emplace_back(PRISM_OIIO_MODULE_PATH);
#endif
  return paths;
}

void load() {
  std::string tried;
  for (const std::string& path : candidatePaths()) {
    if (!fs::exists(path)) {
      tried += "\n  " + path + " (absent)";
      continue;
    }
    // RTLD_LOCAL: OpenImageIO's 260 libraries stay out of the global symbol namespace.
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = ::dlerror();
      tried += "\n  " + path + " (" + (why ? why : "cannot be loaded") + ")";
      continue;
    }
    auto entry = reinterpret_cast<OiioModuleEntry>(::dlsym(handle, kOiioModuleEntryName));
    const OiioModuleApi* api = entry ? entry() : nullptr;
    if (!api || api->version != kOiioModuleVersion) {
      tried += "\n  " + path + " (not a prism_image_oiio module of this build)";
      ::dlclose(handle);
      continue;
    }
    loaded = api;  // never unloaded: OpenImageIO keeps threads and caches until exit
    return;
  }
  loadError = "OpenImageIO's module " + std::string(kModuleFile) +
              " was not found; looked at:" + tried +
              "\n(it is built with prism; set PRISM_OIIO_MODULE to its path if it was moved. PNG "
              "and EXR need no module.)";
}

}  // namespace

const OiioModuleApi& oiioModule(const std::string& what) {
  std::call_once(loadOnce, load);
  const OiioModuleApi* api = loaded.load();
  if (!api) throw std::runtime_error(what + ": " + loadError);
  return *api;
}

bool oiioModuleLoaded() {
  return loaded.load() != nullptr;
}

}  // namespace prism

#include "image/OiioModule.h"

#include <atomic>
#include <mutex>
#include <stdexcept>

#include "util/PluginModule.h"

namespace prism {
namespace {

std::once_flag loadOnce;
std::atomic<const OiioModuleApi*> loaded{nullptr};
std::string loadError;

void load() {
  PluginModuleSearch search;
  search.fileName = "prism_image_oiio.so";
  search.environmentVariable = "PRISM_OIIO_MODULE";
#ifdef PRISM_OIIO_MODULE_PATH
  search.buildPath = PRISM_OIIO_MODULE_PATH;
#endif
  search.entryName = kOiioModuleEntryName;
  // RTLD_LOCAL (global = false): OpenImageIO's 260 libraries stay out of the global namespace.
  const OiioModuleApi* api = nullptr;
  std::string tried;
  loadPluginModule(
      search,
      [&api](void* entry) {
        const OiioModuleApi* candidate = reinterpret_cast<OiioModuleEntry>(entry)();
        if (!candidate || candidate->version != kOiioModuleVersion) return false;
        api = candidate;
        return true;
      },
      &tried);
  if (api) {
    loaded = api;
    return;
  }
  loadError =
      pluginModuleNotFound("OpenImageIO's module", search, tried, "PNG and EXR need no module.");
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

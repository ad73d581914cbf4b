#include "image/OiioModule.h"

#include <atomic>
#include <mutex>
#include <stdexcept>

#include "util/PluginModule.h"

#ifndef PRISM_OIIO_MODULE_PATH
#define PRISM_OIIO_MODULE_PATH ""  // set by the build; without it, only next to the executable
#endif

namespace prism {
namespace {

std::once_flag loadOnce;
std::atomic<const OiioModuleApi*> loaded{nullptr};
std::string loadError;

void load() {
  const PluginModuleSearch search{.fileName = "prism_image_oiio.so",
                                  .environmentVariable = "PRISM_OIIO_MODULE",
                                  .buildPath = PRISM_OIIO_MODULE_PATH,
                                  .entryName = kOiioModuleEntryName};
  // RTLD_LOCAL (global = false): OpenImageIO's 260 libraries stay out of the global namespace.
  std::string tried;
  const OiioModuleApi* api = loadPluginApi<OiioModuleApi>(search, kOiioModuleVersion, &tried);
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

// Part of the executable, not of the module: finds and loads prism_viewer.so (gui/ViewerModule.h).
#include <mutex>
#include <stdexcept>

#include "gui/ViewerModule.h"
#include "util/PluginModule.h"

namespace prism {
namespace {

const ViewerModuleApi& viewerModule() {
  static std::once_flag loadOnce;
  static const ViewerModuleApi* loaded = nullptr;
  static std::string loadError;
  std::call_once(loadOnce, [] {
    PluginModuleSearch search;
    search.fileName = "prism_viewer.so";
    search.environmentVariable = "PRISM_VIEWER_MODULE";
#ifdef PRISM_VIEWER_MODULE_PATH
    search.buildPath = PRISM_VIEWER_MODULE_PATH;
#endif
    search.entryName = kViewerModuleEntryName;
    std::string tried;
    loadPluginModule(
        search,
        [](void* entry) {
          const ViewerModuleApi* api = reinterpret_cast<ViewerModuleEntry>(entry)();
          if (!api || api->version != kViewerModuleVersion) return false;
          loaded = api;
          return true;
        },
        &tried);
    if (!loaded) loadError = pluginModuleNotFound("the viewer's module", search, tried, "");
  });
  if (!loaded) throw std::runtime_error(loadError);
  return *loaded;
}

}  // namespace

ViewerRunner lazyViewerRunner() {
  return [](const Scene& scene, const SceneDescription& description, const ViewOptions& options,
            Transport* session, std::ostream& out, std::ostream& err) {
    return viewerModule().runViewer(scene, description, options, session, out, err);
  };
}

ChartWriter lazyChartWriter() {
  return [](const Chart& chart, const std::string& pngPath) {
    viewerModule().writeChartImage(chart, pngPath);
  };
}

}  // namespace prism

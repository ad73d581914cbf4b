// Part of the executable, not of the module: finds and loads prism_viewer.so (gui/ViewerModule.h).
#include <mutex>
#include <stdexcept>

#include "gui/ViewerModule.h"
#include "util/PluginModule.h"

#ifndef PRISM_VIEWER_MODULE_PATH
#define PRISM_VIEWER_MODULE_PATH ""  // set by the build; without it, only next to the executable
#endif

namespace prism {
namespace {

const ViewerModuleApi& viewerModule() {
  static std::once_flag loadOnce;
  static const ViewerModuleApi* loaded = nullptr;
  static std::string loadError;
  std::call_once(loadOnce, [] {
    const PluginModuleSearch search{.fileName = "prism_viewer.so",
                                    .environmentVariable = "PRISM_VIEWER_MODULE",
                                    .buildPath = PRISM_VIEWER_MODULE_PATH,
                                    .entryName = kViewerModuleEntryName};
    std::string tried;
    loaded = loadPluginApi<ViewerModuleApi>(search, kViewerModuleVersion, &tried);
    if (!loaded) loadError = pluginModuleNotFound("the viewer's module", search, tried, "");
  });
  if (!loaded) throw std::runtime_error(loadError);
  return *loaded;
}

}  // namespace

ViewerRunner lazyViewerRunner() {
  return [](LiveSource& source, const ViewerOptions& options, std::ostream& out,
            std::ostream& err) { return viewerModule().runViewer(source, options, out, err); };
}

ChartWriter lazyChartWriter() {
  return [](const Chart& chart, const std::string& pngPath) {
    viewerModule().writeChartImage(chart, pngPath);
  };
}

}  // namespace prism

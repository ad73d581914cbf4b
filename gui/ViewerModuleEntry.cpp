// The entry point of prism_viewer.so (gui/ViewerModule.h).
#include "gui/ChartImage.h"
#include "gui/Viewer.h"
#include "gui/ViewerModule.h"

namespace {

const prism::ViewerModuleApi kApi{prism::kViewerModuleVersion, &prism::runViewer,
                                  &prism::writeChartImage};

}  // namespace

extern "C" __attribute__((visibility("default"))) const prism::ViewerModuleApi*
prismViewerModule() {
  return &kApi;
}

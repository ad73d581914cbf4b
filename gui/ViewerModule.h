// The viewer and the chart images, loaded on first use. Qt's 34 libraries cost every process
// about 26 ms and 11 MiB at start-up (docs/dependencies.md), though only `prism view` and the
// charts of `prism speedup` and `prism sweep` use them; so gui/ is also built as a module,
// prism_viewer.so, that the executable dlopen()s when one of them is first called. The module
// resolves Prism's symbols against the executable, which exports them. (The GUI tests link gui/
// directly.) This header includes no Qt.
#pragma once

#include <string>

#include "master/analysis/Chart.h"
#include "master/live/ViewerRunner.h"

namespace prism {

// What the module exports. kViewerModuleVersion guards against a module of another build.
// 2: runViewer takes the MasterSession. 3: it takes a LiveSource and the ViewerOptions.
inline constexpr int kViewerModuleVersion = 3;

struct ViewerModuleApi {
  int version;
  int (*runViewer)(LiveSource& source, const ViewerOptions& options, std::ostream& out,
                   std::ostream& err);
  void (*writeChartImage)(const Chart& chart, const std::string& pngPath);
};

extern "C" {
using ViewerModuleEntry = const ViewerModuleApi* (*)();
}
inline constexpr const char* kViewerModuleEntryName = "prismViewerModule";

// Runners that load the module on their first call (next to the executable, then where the build
// put it; $PRISM_VIEWER_MODULE replaces both). Loading failures throw std::runtime_error naming
// where it was looked for.
ViewerRunner lazyViewerRunner();
ChartWriter lazyChartWriter();

}  // namespace prism

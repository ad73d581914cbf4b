// Draws a chart (master/analysis/Chart.h: the charts of `prism speedup` and `prism sweep`) with Qt
// Charts into a PNG, with no display needed: without one, Qt's offscreen platform is chosen before
// the application starts. Matches ChartWriter.
#pragma once

#include <string>

#include "master/analysis/Chart.h"

namespace prism {

// Throws std::runtime_error when the image cannot be written.
void writeChartImage(const Chart& chart, const std::string& pngPath);

}  // namespace prism

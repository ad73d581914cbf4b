// Draws the charts of `prism speedup` (master/SpeedupChart.h) with Qt Charts into a PNG, with
// no display needed: without one, Qt's offscreen platform is chosen before the application
// starts. Matches SpeedupChartWriter.
#pragma once

#include <string>

#include "master/SpeedupChart.h"

namespace prism {

// Throws std::runtime_error when the image cannot be written.
void writeSpeedupChartImage(const SpeedupChart& chart, const std::string& pngPath);

}  // namespace prism

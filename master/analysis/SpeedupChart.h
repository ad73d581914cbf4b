// The charts of `prism speedup` (master/analysis/Chart.h), from its report.
#pragma once

#include "master/analysis/Chart.h"
#include "master/analysis/SpeedupReport.h"

namespace prism {

// Speedup and efficiency against p for every measured series (schedule and tile size), with
// the ideal line; oversubscribed points marked.
Chart measuredChart(const SpeedupReport& report);
// The measured points of the T1 tile size with the model's curves: its prediction at the
// measured size and its projection to larger images and p up to the plan's maximum.
Chart projectionChart(const SpeedupReport& report);

}  // namespace prism

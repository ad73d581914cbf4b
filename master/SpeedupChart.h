// The charts of `prism speedup` as plain data: panels of named series, which gui/ draws with
// Qt Charts (gui/SpeedupChartImage.h) and master/ hands over through SpeedupChartWriter, so the
// measurement builds and runs without Qt.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "master/SpeedupReport.h"

namespace prism {

struct ChartSeries {
  enum class Kind { Measured, Model, Ideal };
  std::string name;
  Kind kind = Kind::Measured;
  std::vector<double> x, y;
  std::vector<bool> oversubscribed;  // per point (measured series); marked on the chart
};

struct ChartPanel {
  std::string title, xTitle, yTitle;
  bool logX = false, logY = false;
  std::vector<ChartSeries> series;
};

struct SpeedupChart {
  std::string title;
  std::string note;  // a line under the title: machine, repeats, what is oversubscribed
  std::vector<ChartPanel> panels;
};

// Draws the chart into a PNG file; throws std::runtime_error on failure. Empty in a build
// without Qt, where `prism speedup` writes the table and CSVs and says the charts need Qt.
using SpeedupChartWriter = std::function<void(const SpeedupChart&, const std::string& pngPath)>;

// Speedup and efficiency against p for every measured series (schedule and tile size), with
// the ideal line; oversubscribed points marked.
SpeedupChart measuredChart(const SpeedupReport& report);
// The measured points of the T1 tile size with the model's curves: its prediction at the
// measured size and its projection to larger images and p up to the plan's maximum.
SpeedupChart projectionChart(const SpeedupReport& report);

}  // namespace prism

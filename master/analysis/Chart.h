// Charts as plain data: panels of named series, and strips of captioned thumbnails. master/
// builds them (`prism speedup`, `prism sweep`), gui/ draws them with Qt Charts offscreen
// (gui/ChartImage.h) and hands the drawing over through a ChartWriter, so the measurements build
// and run without Qt.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "image/ImageRgb.h"

namespace prism {

struct ChartSeries {
  // Measured: a solid line with points. Model and Ideal: dashed. Front: a thick black line
  // behind the others (the Pareto front of `prism sweep`).
  enum class Kind { Measured, Model, Ideal, Front };
  std::string name;
  Kind kind = Kind::Measured;
  std::vector<double> x, y;
  std::vector<bool> marked;  // per point: drawn with a hollow square (see ChartPanel::markedName)
};

struct ChartPanel {
  std::string title, xTitle, yTitle;
  bool logX = false, logY = false;
  std::vector<ChartSeries> series;
  double logBase = 2.0;    // of the logarithmic axes
  std::string markedName;  // the legend's name for marked points, e.g. "oversubscribed"
};

// A row of small images along one curve, each with a caption (its settings and error).
struct Thumbnail {
  ImageRgb image;  // linear radiance
  std::string caption;
};
struct ThumbnailStrip {
  std::string title;
  float exposure = 1.0f;  // radiance multiplier before the sRGB curve
  std::vector<Thumbnail> thumbnails;
};

struct Chart {
  std::string title;
  std::string note;  // a line under the title: machine, repeats, what the marks mean
  std::vector<ChartPanel> panels;
  std::vector<ThumbnailStrip> strips;  // drawn under the panels
};

// Draws the chart into a PNG file; throws std::runtime_error on failure. Empty in a build
// without Qt, where the commands write their tables and CSVs and say the charts need Qt.
using ChartWriter = std::function<void(const Chart&, const std::string& pngPath)>;

}  // namespace prism

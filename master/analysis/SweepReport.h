// What `prism sweep` measured, and its outputs: the CSV (one row per point), the terminal table
// and the chart (error against time, log-log, one curve per family, the Pareto front, thumbnail
// strips along the curves).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "image/ImageError.h"
#include "master/analysis/Chart.h"
#include "master/analysis/SweepPlan.h"
#include "master/analysis/SweepReference.h"

namespace prism {

// The error the chart and the Pareto front use. MRSE by default: per-pixel relative error is
// not dominated by a few very bright pixels (a focused caustic's peak), which RMSE-based
// numbers are (docs/accuracy.md).
enum class SweepMetric { Mrse, RelRmse, Rmse, MaxError };
const char* metricName(SweepMetric metric);

struct SweepRow {
  SweepPoint point;
  std::vector<double> seconds, cpuSeconds;  // one per timed run
  ImageError image, region;                 // whole frame, caustic region
  bool pareto = false;
  ImageRgb thumbnail;  // the caustic region of this point's image

  double medianSeconds() const;
  double medianCpuSeconds() const;
  // The time the chart and the front use: wall or CPU seconds.
  double cost(bool cpuAxis) const { return cpuAxis ? medianCpuSeconds() : medianSeconds(); }
  // The metric in the caustic region, or over the whole frame when the reference has no
  // caustic light.
  double error(SweepMetric metric) const;
};

struct SweepReport {
  std::string scenePath;
  int width = 0, height = 0, samplesPerPixel = 0, threads = 0, cores = 0;
  int repeats = 0;       // runs asked for per point
  bool cpuAxis = false;  // chart CPU seconds instead of wall seconds
  SweepMetric metric = SweepMetric::Mrse;
  bool budgetHit = false;  // --budget-seconds stopped the sweep early
  float exposure = 1.0f;
  std::string referenceKind, referenceDescription;
  bool referenceCached = false;
  size_t regionPixels = 0;
  std::vector<ReferenceConvergence> convergence;
  ImageRgb referenceThumbnail, baseThumbnail;
  std::vector<SweepRow> rows;  // points with at least one run
  size_t plannedPoints = 0;
};

// Sets each row's pareto flag: no other row is both as fast and as accurate.
void markParetoFront(SweepReport& report);

// The CSV's columns, in order (the schema is tested).
const std::vector<std::string>& sweepCsvColumns();
void writeSweepCsv(const SweepReport& report, std::ostream& out);

// One line per point: family, value, median time, errors, flux ratio, front membership.
void printSweepTable(const SweepReport& report, std::ostream& out);

// Two panels against time (log x): the metric in the caustic region (log y, with the Pareto
// front), and the caustic flux ratio; a thumbnail strip per family and one for the reference.
Chart sweepChart(const SweepReport& report);

}  // namespace prism

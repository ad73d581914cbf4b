// `prism sweep`: speed against accuracy. Renders the scene with each caustic method over a range
// of budgets (master/analysis/SweepPlan.h), times every point (median of repeated runs, in rounds
// so that drift on a busy machine spreads over all points), scores each image against a reference
// (master/analysis/SweepReference.h) with the metrics of image/ImageError.h over the whole frame
// and the caustic region, and writes PREFIX.csv and the chart PREFIX.png
// (master/analysis/SweepReport.h). One process: the render threads of this machine, no MPI slaves.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "master/analysis/Chart.h"
#include "master/analysis/SweepPlan.h"
#include "master/analysis/SweepReference.h"
#include "master/analysis/SweepReport.h"
#include "master/commands/RenderCommand.h"

namespace prism {

struct SweepOptions {
  RenderOptions render;      // scene, threads, size/spp/seed overrides
  std::string outputPrefix;  // empty: sweep-<scene name>
  std::vector<SweepFamily> families = defaultSweepFamilies();
  SweepValues values;
  int repeats = 3;
  ReferenceRequest reference;              // its cacheStem defaults to PREFIX-reference
  double budgetSeconds = 0.0;              // 0: no limit; else no run starts after this long
  bool cpuAxis = false;                    // chart CPU seconds instead of wall seconds
  SweepMetric metric = SweepMetric::Mrse;  // the chart's error and the Pareto front's
  int thumbnailHeight = 96;
  bool quiet = false;  // no progress bar and no table
};

// The files a sweep writes, from the prefix.
struct SweepOutputs {
  std::string csv, chart, referenceStem;
};
SweepOutputs sweepOutputs(const std::string& prefix);

// Runs the command; returns the exit code. chartWriter is empty without Qt: then only the CSV
// is written, with a note. In an MPI job of more than one rank it refuses (the slaves stop).
int runSweep(const SweepOptions& options, std::ostream& out, std::ostream& err, Transport* session,
             const ChartWriter& chartWriter);

}  // namespace prism

// `prism speedup`: strong-scaling measurement inside one MPI job. Rank 0 coordinates; the same
// frame is rendered by 1, 2, ..., N−1 slaves (the others idle) under each schedule and tile
// size asked for, and by one process on one thread (T1, no MPI) for the baseline. Each point
// is repeated and reported as a median with its spread; set-up (parse, broadcast, scene build,
// photon pass or caustic map) is timed apart. The link is measured, the tile queue is
// simulated with the measured costs to validate the model on the measured points and to
// project past this machine. Output: a table, two CSVs and two charts (docs/scaling.md).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "master/analysis/SpeedupChart.h"
#include "master/commands/RenderCommand.h"

namespace prism {

struct SpeedupOptions {
  RenderOptions render;      // scene path, overrides (size, spp, caustics), prefetch, lease
  std::string outputPrefix;  // empty: speedup-<scene name> in the current folder
  std::vector<Schedule> schedules{Schedule::Dynamic, Schedule::Static};
  std::vector<int> tileSizes;  // empty: the automatic size for N−1 slaves
  int threadsPerRank = 1;      // render threads of each slave
  int repeats = 5;
  int linkRoundTrips = 20;  // per message size and slave
  int projectWorkers = 1024;
  bool quiet = false;  // no progress bar
};

// The files a run writes, from the prefix.
struct SpeedupOutputs {
  std::string csv, projectionCsv, chart, projectionChart;
};
SpeedupOutputs speedupOutputs(const std::string& prefix);

// Runs the command; returns the exit code. Needs an MPI job of at least 2 ranks: without one it
// explains how to start it and fails. chartWriter is empty without Qt: the charts are skipped
// with a note.
int runSpeedup(const SpeedupOptions& options, std::ostream& out, std::ostream& err,
               Transport* session, const ChartWriter& chartWriter);

}  // namespace prism

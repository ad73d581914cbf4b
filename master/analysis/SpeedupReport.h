// What `prism speedup` measured, and the three ways it is written out: a table for the
// terminal, a CSV (one row per measured point; docs/scaling.md lists the columns), and a CSV of
// the projection. Also the per-point statistics derived from the timings (speedup, efficiency,
// Karp–Flatt, the Amdahl fit of each series). No MPI, no clock: tested on synthetic timings.
#pragma once

#include <cmath>
#include <iosfwd>
#include <limits>
#include <string>
#include <vector>

#include "master/analysis/LinkProbe.h"
#include "master/analysis/ScalingMetrics.h"
#include "master/dispatch/TileScheduler.h"

namespace prism {

// One frame configuration measured `repeats` times: `slaves` ranks of `threadsPerRank` threads
// render, rank 0 coordinates, the other slaves idle.
struct ScalingPoint {
  Schedule schedule = Schedule::Dynamic;
  int tileSize = 0;
  int slaves = 0;
  int threadsPerRank = 1;
  std::vector<double> samples;  // frame seconds, one per repeat
  // Per active slave, one entry per repeat: its threads' rendering time over (threads × frame).
  std::vector<std::vector<double>> busyFractions;
  bool oversubscribed = false;  // slaves × threads + rank 0 > cores
  double modelSeconds = std::numeric_limits<double>::quiet_NaN();  // the simulator's

  // Derived by deriveStatistics:
  TimingSpread seconds;
  double speedup = 0.0, efficiency = 0.0, karpFlatt = 0.0;
  std::vector<double> workerBusy;  // per active slave: median busy fraction
  double amdahlFraction = 0.0;     // of the point's series
  double amdahlSpeedup = 0.0;

  int workers() const { return slaves * threadsPerRank; }
  std::string series() const;  // "dynamic-32": schedule and tile size
};

// The serial baseline: 1 process, 1 thread, no MPI, at one tile size.
struct SerialPoint {
  int tileSize = 0;
  std::vector<double> samples;
  TimingSpread seconds;
};

// Set-up, timed once and kept out of every frame time.
struct SpeedupSetup {
  // Rank 0's start, before the command: from its parent's start (under mpirun on one node, the
  // launcher's share; -1 where /proc cannot say), from its own start to the command (loading
  // libraries and MPI), and MPI_Init alone within that.
  double launchSeconds = -1.0;
  double startSeconds = -1.0;
  double mpiInitSeconds = 0.0;
  double parseSeconds = 0.0;
  double broadcastSeconds = 0.0;
  size_t broadcastBytes = 0;
  double buildSeconds = 0.0;       // rank 0's Scene (BVH)
  double slaveBuildSeconds = 0.0;  // the slowest slave's
  // The slaves' own starts, the slowest of each: process start to command (-1: not known), and
  // MPI_Init.
  double slaveStartSeconds = -1.0;
  double slaveMpiInitSeconds = 0.0;
  std::string causticStage;  // "photon pass", "caustic map", or empty
  double causticSeconds = 0.0;
};

struct ProjectedPoint {
  int width = 0, height = 0, tileSize = 0;
  Schedule schedule = Schedule::Dynamic;
  int workers = 0;
  double seconds = 0.0;        // simulated frame time
  double serialSeconds = 0.0;  // the same tiles on one thread, no messages
  double speedup() const { return serialSeconds / seconds; }
};

// The viewer's real-time frames as the model projects them: 1 sample per pixel, every frame at
// full resolution, one after another (docs/viewer.md).
struct FrameRatePoint {
  int width = 0, height = 0;
  int workers = 0;                          // render threads over all ranks
  double framesPerSecond = 0.0;             // pipelined, as the viewer renders
  double unpipelinedFramesPerSecond = 0.0;  // each frame waiting for its last result
  double resultBytesPerSecond = 0.0;        // tile results reaching rank 0 at the pipelined rate
};

struct SpeedupReport {
  std::string scenePath;
  int width = 0, height = 0, samplesPerPixel = 0;
  int ranks = 0;  // in the MPI job
  int cores = 0;  // of rank 0's machine
  int threadsPerRank = 1;
  int repeats = 0;
  int prefetch = 0;
  std::string instructionSet;  // the kernels' set on every rank, and why (JobInstructionSet)
  SpeedupSetup setup;
  LinkMeasurement link;
  std::vector<SerialPoint> serial;
  double serialSeconds = 0.0;  // T1: the best serial median
  int serialTileSize = 0;
  std::vector<ScalingPoint> points;
  std::vector<ProjectedPoint> projection;
  std::vector<FrameRatePoint> frameRates;

  // Mean |model − measured| / measured over the points, and over those not oversubscribed
  // (NaN when there are none).
  double modelError(bool includeOversubscribed) const;
};

// Fills the derived fields: spreads, T1 (the fastest serial median), and per point speedup,
// efficiency, Karp–Flatt, median busy fractions and the series' Amdahl fit.
void deriveStatistics(SpeedupReport& report);

// The CSV columns, in order; the first four that the viewer needs (gui/SpeedupCsv.h) among them.
const std::vector<std::string>& speedupCsvColumns();
// Comment lines (#) describing the run, the header, then one row per measured point. Rows are
// in the order measured points are listed, so the viewer, which charts the first series,
// charts the first schedule and tile size asked for.
void writeSpeedupCsv(const SpeedupReport& report, std::ostream& out);
void writeProjectionCsv(const SpeedupReport& report, std::ostream& out);
void printSpeedupTable(const SpeedupReport& report, std::ostream& out);

const char* scheduleName(Schedule schedule);

}  // namespace prism

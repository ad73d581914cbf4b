// The scheduling model of `prism speedup`: the simulator (master/analysis/TileScheduleSimulator.h)
// fed with the measured tile costs and link, used twice — to predict the measured points (the
// model's validation) and to project speedup to worker counts and image sizes this machine
// cannot run.
#pragma once

#include <map>
#include <utility>
#include <vector>

#include "master/analysis/SpeedupReport.h"
#include "master/analysis/TileCostMap.h"

namespace prism {

// Sizes of the wire messages the master and a slave exchange per tile (common/wire): a result
// carries radiance, 12 bytes a pixel, or, for a frame only shown (the viewer's frames while
// the camera moves, RenderView::displayExposure), display bytes, 3 a pixel.
double tileJobBytes();
double tileResultBytes(int pixels, bool displayBytes = false);

// The fraction of a core each of `renderThreads` threads gets on `cores` cores.
double cpuShareOf(int renderThreads, int cores);

// Sets modelSeconds of every measured point: its frame simulated with the per-tile serial
// times measured at its tile size (serialTileSeconds[tileSize], in plan order), the measured
// link, and the point's CPU share on report.cores cores.
void predictMeasuredPoints(SpeedupReport& report,
                           const std::map<int, std::vector<double>>& serialTileSeconds);

struct ProjectionPlan {
  std::vector<std::pair<int, int>> sizes;  // width, height
  int tileSize = 32;
  int maxWorkers = 1024;  // p = threadsPerRank, 2·threadsPerRank, ... doubling up to this
  std::vector<Schedule> schedules{Schedule::Dynamic};
};

// Simulated frames for every size, schedule and worker count of the plan; each render thread
// has a core of its own.
std::vector<ProjectedPoint> projectScaling(const TileCostMap& costs, const ProjectionPlan& plan,
                                           const SpeedupReport& report);

// The viewer's real-time frame rate at every size of the plan and worker count (doubling from
// one rank of report.threadsPerRank threads up to plan.maxWorkers), dynamic schedule, the
// measured link. Tile costs are the measured ones scaled from report.samplesPerPixel to 1.
// Results come as display bytes: a moving camera's frames, which a cluster only shows.
// Pipelined (WorkDispatcher::queueFrame): kPipelinedFrames frames' tiles in one queue, their
// count over the time until the last result (the first frame's start-up included, so slightly
// low); unpipelined: one frame on its own, round trip included.
inline constexpr int kPipelinedFrames = 16;
std::vector<FrameRatePoint> projectFrameRates(const TileCostMap& costs, const ProjectionPlan& plan,
                                              const SpeedupReport& report);

// Bytes per second of tile results a stream of width×height frames at framesPerSecond puts on
// rank 0's link (tiles of tileSize, display bytes as above).
double streamBytesPerSecond(int width, int height, int tileSize, double framesPerSecond);

}  // namespace prism

#include "master/analysis/ScalingProjection.h"

#include <algorithm>
#include <numeric>

#include "master/analysis/TileScheduleSimulator.h"
#include "master/frame/TilePlan.h"
#include "wire/Messages.h"

namespace prism {
namespace {

// displayBytes: results of frames only shown (tileResultBytes).
ScheduleSimulation simulationOf(std::vector<double> tileSeconds, const std::vector<TileRect>& tiles,
                                int ranks, Schedule schedule, double cpuShare,
                                const SpeedupReport& r, bool displayBytes = false) {
  ScheduleSimulation s;
  s.tileSeconds = std::move(tileSeconds);
  for (const TileRect& t : tiles) {
    s.resultBytes.push_back(tileResultBytes(t.pixelCount(), displayBytes));
  }
  s.jobBytes = tileJobBytes();
  s.workers = ranks;
  s.threadsPerWorker = r.threadsPerRank;
  s.prefetch = r.prefetch;
  s.schedule = schedule;
  s.link = r.link.model;
  s.cpuShare = cpuShare;
  return s;
}

}  // namespace

double tileJobBytes() {
  return static_cast<double>(wire::encode(wire::TileJobMessage{}).size());
}

double tileResultBytes(int pixels, bool displayBytes) {
  // The envelope and fixed fields, measured on an empty tile (the same either way), then 3
  // floats or 3 bytes a pixel.
  static const double fixed = static_cast<double>(wire::encode(wire::TileResultMessage{}).size());
  return fixed + (displayBytes ? 3.0 : 3.0 * sizeof(float)) * pixels;
}

double cpuShareOf(int renderThreads, int cores) {
  return renderThreads > cores ? static_cast<double>(cores) / renderThreads : 1.0;
}

void predictMeasuredPoints(SpeedupReport& report,
                           const std::map<int, std::vector<double>>& serialTileSeconds) {
  for (ScalingPoint& p : report.points) {
    const auto costs = serialTileSeconds.find(p.tileSize);
    if (costs == serialTileSeconds.end()) continue;
    const std::vector<TileRect> tiles = planTiles(report.width, report.height, p.tileSize);
    const ScheduleSimulation s = simulationOf(costs->second, tiles, p.slaves, p.schedule,
                                              cpuShareOf(p.workers(), report.cores), report);
    p.modelSeconds = simulateTileSchedule(s).seconds;
  }
}

std::vector<ProjectedPoint> projectScaling(const TileCostMap& costs, const ProjectionPlan& plan,
                                           const SpeedupReport& report) {
  std::vector<ProjectedPoint> points;
  for (const auto& [width, height] : plan.sizes) {
    const std::vector<TileRect> tiles = planTiles(width, height, plan.tileSize);
    const std::vector<double> tileSeconds = costs.tileCosts(width, height, plan.tileSize);
    const double serial = std::accumulate(tileSeconds.begin(), tileSeconds.end(), 0.0);
    for (Schedule schedule : plan.schedules) {
      for (int ranks = 1; ranks * report.threadsPerRank <= plan.maxWorkers; ranks *= 2) {
        const ScheduleSimulation s = simulationOf(tileSeconds, tiles, ranks, schedule, 1.0, report);
        ProjectedPoint p;
        p.width = width;
        p.height = height;
        p.tileSize = plan.tileSize;
        p.schedule = schedule;
        p.workers = ranks * report.threadsPerRank;
        p.seconds = simulateTileSchedule(s).seconds;
        p.serialSeconds = serial;
        points.push_back(p);
      }
    }
  }
  return points;
}

double streamBytesPerSecond(int width, int height, int tileSize, double framesPerSecond) {
  double bytes = 0.0;
  for (const TileRect& t : planTiles(width, height, tileSize)) {
    bytes += tileResultBytes(t.pixelCount(), true);
  }
  return bytes * framesPerSecond;
}

std::vector<FrameRatePoint> projectFrameRates(const TileCostMap& costs, const ProjectionPlan& plan,
                                              const SpeedupReport& report) {
  std::vector<FrameRatePoint> points;
  const double perSample = 1.0 / std::max(report.samplesPerPixel, 1);
  for (const auto& [width, height] : plan.sizes) {
    const std::vector<TileRect> tiles = planTiles(width, height, plan.tileSize);
    std::vector<double> tileSeconds = costs.tileCosts(width, height, plan.tileSize);
    for (double& t : tileSeconds) t *= perSample;
    // kPipelinedFrames frames back to back in one dynamic queue.
    std::vector<double> stream;
    std::vector<TileRect> streamTiles;
    for (int f = 0; f < kPipelinedFrames; ++f) {
      stream.insert(stream.end(), tileSeconds.begin(), tileSeconds.end());
      streamTiles.insert(streamTiles.end(), tiles.begin(), tiles.end());
    }
    for (int ranks = 1; ranks * report.threadsPerRank <= plan.maxWorkers; ranks *= 2) {
      const double one = simulateTileSchedule(simulationOf(tileSeconds, tiles, ranks,
                                                           Schedule::Dynamic, 1.0, report, true))
                             .seconds;
      const double many = simulateTileSchedule(simulationOf(stream, streamTiles, ranks,
                                                            Schedule::Dynamic, 1.0, report, true))
                              .seconds;
      FrameRatePoint p;
      p.width = width;
      p.height = height;
      p.workers = ranks * report.threadsPerRank;
      p.unpipelinedFramesPerSecond = one > 0.0 ? 1.0 / one : 0.0;
      p.framesPerSecond = many > 0.0 ? kPipelinedFrames / many : 0.0;
      p.resultBytesPerSecond =
          streamBytesPerSecond(width, height, plan.tileSize, p.framesPerSecond);
      points.push_back(p);
    }
  }
  return points;
}

}  // namespace prism

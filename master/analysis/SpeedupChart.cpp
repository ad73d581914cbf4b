#include "master/analysis/SpeedupChart.h"

#include <algorithm>
#include <cstdio>

namespace prism {
namespace {

ChartSeries ideal(double maxWorkers, bool efficiency) {
  ChartSeries s{"ideal", ChartSeries::Kind::Ideal, {1.0, maxWorkers}, {}, {}};
  s.y = efficiency ? std::vector<double>{1.0, 1.0} : std::vector<double>{1.0, maxWorkers};
  return s;
}

std::string machineNote(const SpeedupReport& r) {
  char note[256];
  std::snprintf(note, sizeof note,
                "%dx%d, %d spp; %d cores, %d MPI ranks (rank 0 coordinates); medians of %d "
                "runs; T1 = %.3f s (1 process, 1 thread); hollow squares: oversubscribed",
                r.width, r.height, r.samplesPerPixel, r.cores, r.ranks, r.repeats, r.serialSeconds);
  return note;
}

}  // namespace

Chart measuredChart(const SpeedupReport& r) {
  Chart chart;
  chart.title = "prism speedup: " + r.scenePath;
  chart.note = machineNote(r);
  ChartPanel speedup{
      "Speedup S = T1 / Tp", "p (slaves x threads)", "speedup", false, false, {}, 2.0,
      "oversubscribed"};
  ChartPanel efficiency{
      "Efficiency E = S / p", "p (slaves x threads)", "efficiency", false, false, {}, 2.0,
      "oversubscribed"};
  double maxWorkers = 1.0;
  for (const ScalingPoint& p : r.points) {
    maxWorkers = std::max(maxWorkers, static_cast<double>(p.workers()));
    auto it = std::find_if(speedup.series.begin(), speedup.series.end(),
                           [&](const ChartSeries& s) { return s.name == p.series(); });
    if (it == speedup.series.end()) {
      speedup.series.push_back({p.series(), ChartSeries::Kind::Measured, {}, {}, {}});
      efficiency.series.push_back({p.series(), ChartSeries::Kind::Measured, {}, {}, {}});
      it = speedup.series.end() - 1;
    }
    ChartSeries& e = efficiency.series[static_cast<size_t>(it - speedup.series.begin())];
    it->x.push_back(p.workers());
    it->y.push_back(p.speedup);
    it->marked.push_back(p.oversubscribed);
    e.x.push_back(p.workers());
    e.y.push_back(p.efficiency);
    e.marked.push_back(p.oversubscribed);
  }
  speedup.series.insert(speedup.series.begin(), ideal(maxWorkers, false));
  efficiency.series.insert(efficiency.series.begin(), ideal(maxWorkers, true));
  chart.panels = {speedup, efficiency};
  return chart;
}

Chart projectionChart(const SpeedupReport& r) {
  Chart chart;
  chart.title = "prism speedup, measured and projected: " + r.scenePath;
  char note[256];
  std::snprintf(note, sizeof note,
                "model: pull-queue simulation replaying the measured tile costs, latency "
                "%.2f ms and bandwidth %.0f MB/s; error on measured points %.1f%% "
                "(not oversubscribed)",
                r.link.model.latencySeconds * 1e3, r.link.model.bytesPerSecond / 1e6,
                r.modelError(false) * 100);
  chart.note = note;
  ChartPanel speedup{"Speedup S = T1 / Tp (dynamic, tile " + std::to_string(r.serialTileSize) + ")",
                     "p (workers)",
                     "speedup",
                     true,
                     true,
                     {},
                     2.0,
                     "oversubscribed"};
  ChartPanel efficiency{"Efficiency E = S / p", "p (workers)", "efficiency", true, false, {}, 2.0,
                        "oversubscribed"};
  double maxWorkers = 1.0;
  for (const ProjectedPoint& p : r.projection) {
    if (p.schedule != Schedule::Dynamic) continue;
    maxWorkers = std::max(maxWorkers, static_cast<double>(p.workers));
    const std::string name = "model " + std::to_string(p.width) + "x" + std::to_string(p.height);
    auto it = std::find_if(speedup.series.begin(), speedup.series.end(),
                           [&](const ChartSeries& s) { return s.name == name; });
    if (it == speedup.series.end()) {
      speedup.series.push_back({name, ChartSeries::Kind::Model, {}, {}, {}});
      efficiency.series.push_back({name, ChartSeries::Kind::Model, {}, {}, {}});
      it = speedup.series.end() - 1;
    }
    ChartSeries& e = efficiency.series[static_cast<size_t>(it - speedup.series.begin())];
    it->x.push_back(p.workers);
    it->y.push_back(p.speedup());
    e.x.push_back(p.workers);
    e.y.push_back(p.speedup() / p.workers);
  }
  ChartSeries measured{"measured " + std::to_string(r.width) + "x" + std::to_string(r.height),
                       ChartSeries::Kind::Measured,
                       {},
                       {},
                       {}};
  ChartSeries measuredEfficiency = measured;
  for (const ScalingPoint& p : r.points) {
    if (p.schedule != Schedule::Dynamic || p.tileSize != r.serialTileSize) continue;
    measured.x.push_back(p.workers());
    measured.y.push_back(p.speedup);
    measured.marked.push_back(p.oversubscribed);
    measuredEfficiency.x.push_back(p.workers());
    measuredEfficiency.y.push_back(p.efficiency);
    measuredEfficiency.marked.push_back(p.oversubscribed);
  }
  speedup.series.insert(speedup.series.begin(), ideal(maxWorkers, false));
  efficiency.series.insert(efficiency.series.begin(), ideal(maxWorkers, true));
  if (!measured.x.empty()) {
    speedup.series.push_back(measured);
    efficiency.series.push_back(measuredEfficiency);
  }
  chart.panels = {speedup, efficiency};
  return chart;
}

}  // namespace prism

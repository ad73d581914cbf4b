#include "master/commands/SpeedupCommand.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <ostream>
#include <utility>

#include "caustics/CausticMapEstimator.h"
#include "caustics/GatherRadius.h"
#include "caustics/PhotonGather.h"
#include "caustics/PhotonTracer.h"
#include "master/analysis/LinkProbe.h"
#include "master/analysis/ScalingProjection.h"
#include "master/analysis/TileCostMap.h"
#include "master/commands/MasterSession.h"
#include "master/commands/ProgressBar.h"
#include "master/frame/CausticPasses.h"
#include "master/frame/FrameRenderer.h"
#include "master/frame/PhotonPass.h"
#include "master/frame/TilePlan.h"
#include "scene/Scene.h"
#include "transport/Transport.h"
#include "util/AtomicFile.h"
#include "util/Parallel.h"
#include "util/ProcessStart.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {
namespace {

constexpr double kReadyTimeoutSeconds = 600.0;

// The light terms every measured frame renders, prepared once as set-up.
struct PreparedPass {
  std::shared_ptr<const RenderPass> pass;  // null: direct light only
  std::string stage;                       // what the set-up was, for the report
  double seconds = 0.0;
  bool progressiveAsOneFrame = false;
};

// Caustics as `prism render` would do them for one frame: one photon pass traced by every
// rank and sent to every slave, or rank 0's caustic maps (each slave builds its own during
// the warm-up frame). A progressive scene is measured as one k-NN photon-map frame.
PreparedPass prepareCaustics(WorkDispatcher& dispatcher) {
  const Scene& scene = dispatcher.scene();
  const CausticSettings& settings = scene.causticSettings();
  PreparedPass prepared;
  const auto start = SteadyClock::now();
  if (settings.method == CausticMethod::CausticMap) {
    auto maps = std::make_shared<const CausticMapEstimator>(scene, dispatcher.localThreads());
    prepared.stage = "caustic map (rank 0)";
    prepared.pass = RenderPass::withCausticMaps(0, std::move(maps));
  } else if (settings.method == CausticMethod::PhotonMap) {
    const PhotonTracer tracer(scene, settings.photons, settings.maxBounces);
    if (tracer.hasWork()) {
      PhotonPassStats stats;
      const float radius =
          settings.maxRadius > 0.0f ? settings.maxRadius : automaticMaxRadius(scene);
      const PhotonGatherSettings gather = classicGather(settings, radius);
      auto estimator =
          runPhotonPass(tracer, 0, gather, dispatcher.localThreads(), dispatcher, stats);
      prepared.stage = "photon pass (" + std::to_string(estimator->map().size()) + " photons)";
      prepared.pass = RenderPass::withPhotons(0, true, std::move(estimator));
      prepared.progressiveAsOneFrame = settings.progressive;
    }
  }
  prepared.seconds = secondsSince(start);
  return prepared;
}

// Waits for every slave's Ready (its scene is built); the roster then holds their start and
// build times.
void waitForSlaves(SlaveLink& link) {
  const auto start = SteadyClock::now();
  auto missing = [&] {
    int count = 0;
    for (int r = 1; r < link.ranks(); ++r) count += link.ready(r) ? 0 : 1;
    return count;
  };
  while (missing() > 0) {
    if (secondsSince(start) > kReadyTimeoutSeconds) {
      throw std::runtime_error("slaves did not report ready within " +
                               std::to_string(static_cast<int>(kReadyTimeoutSeconds)) + " s");
    }
    link.receive(0.1);  // a Ready goes into the roster; nothing else is expected yet
  }
}

class Measurement {
 public:
  Measurement(WorkDispatcher& dispatcher, const SpeedupOptions& options,
              std::shared_ptr<const RenderPass> pass)
      : dispatcher_(dispatcher),
        serial_(dispatcher.scene(), nullptr, serialOptions()),
        options_(options),
        pass_(std::move(pass)) {}

  // The serial baseline: this process, one thread, no slaves (a dispatcher of its own, kept for
  // every serial frame).
  FrameResult serial(int tileSize) {
    FrameOptions frame;
    frame.distribution = serialOptions();
    frame.distribution.tileSize = tileSize;
    frame.pass = pass_;
    frame.frameId = nextFrame_++;
    return renderFrame(serial_, frame);
  }

  FrameResult parallel(Schedule schedule, int tileSize, int slaves) {
    FrameOptions frame;
    frame.distribution = options_.render.distribution;
    frame.distribution.tileSize = tileSize;
    frame.distribution.schedule = schedule;
    frame.pass = pass_;
    frame.masterRenders = false;
    frame.activeSlaves = slaves;
    frame.frameId = nextFrame_++;
    FrameResult result = renderFrame(dispatcher_, frame);
    for (int r = 1; r <= slaves; ++r) {
      if (result.workers[r].retired) {
        throw std::runtime_error("rank " + std::to_string(r) +
                                 " stopped answering during a measured frame; its numbers would "
                                 "be meaningless");
      }
    }
    return result;
  }

 private:
  static DistributionOptions serialOptions() {
    DistributionOptions o;
    o.threads = 1;
    return o;
  }

  WorkDispatcher& dispatcher_;
  WorkDispatcher serial_;
  const SpeedupOptions& options_;
  std::shared_ptr<const RenderPass> pass_;
  uint32_t nextFrame_ = 1;
};

// Per-tile medians over the serial repeats, in plan order.
std::vector<double> medianTileSeconds(const std::vector<std::vector<double>>& runs) {
  std::vector<double> medians(runs.front().size());
  for (size_t tile = 0; tile < medians.size(); ++tile) {
    std::vector<double> samples;
    for (const std::vector<double>& run : runs) samples.push_back(run[tile]);
    medians[tile] = spreadOf(samples).median;
  }
  return medians;
}

void writeOutputs(const SpeedupReport& report, const SpeedupOutputs& files,
                  const ChartWriter& chartWriter, std::ostream& out, std::ostream& err) {
  writeFileAtomically(files.csv, [&](std::ostream& f) { writeSpeedupCsv(report, f); });
  writeFileAtomically(files.projectionCsv, [&](std::ostream& f) { writeProjectionCsv(report, f); });
  out << "\n  wrote " << files.csv << " and " << files.projectionCsv << "\n";
  if (!chartWriter) {
    err << "prism: note: the charts need Qt5 Charts, which this build lacks; the CSVs hold every "
           "number\n";
    return;
  }
  chartWriter(measuredChart(report), files.chart);
  chartWriter(projectionChart(report), files.projectionChart);
  out << "  wrote " << files.chart << " and " << files.projectionChart << "\n";
}

}  // namespace

SpeedupOutputs speedupOutputs(const std::string& prefix) {
  return {prefix + ".csv", prefix + "-projection.csv", prefix + "-speedup.png",
          prefix + "-projection.png"};
}

namespace {

// The set-up figures the report prints: rank 0's from the session, the slowest slave's from
// the roster (once every slave said Ready).
void recordSetUp(MasterSession& session, SpeedupReport& report) {
  const SessionSetUp& setUp = session.setUp();
  report.setup.parseSeconds = setUp.parseSeconds;
  report.setup.broadcastSeconds = setUp.broadcastSeconds;
  report.setup.broadcastBytes = setUp.broadcastBytes;
  report.setup.buildSeconds = setUp.buildSeconds;
  report.instructionSet = setUp.instructionSet.describe();
  const RenderSettings& settings = session.scene().settings();
  report.width = settings.width;
  report.height = settings.height;
  report.samplesPerPixel = settings.samplesPerPixel;
  for (const RankStats& slave : session.link().roster()) {
    if (slave.rank == 0) continue;
    report.setup.slaveBuildSeconds = std::max(report.setup.slaveBuildSeconds, slave.buildSeconds);
    report.setup.slaveStartSeconds = std::max(report.setup.slaveStartSeconds, slave.startSeconds);
    report.setup.slaveMpiInitSeconds =
        std::max(report.setup.slaveMpiInitSeconds, slave.mpiInitSeconds);
  }
}

// The measured points: every schedule, tile size and slave count.
void planPoints(const SpeedupOptions& options, const std::vector<int>& tileSizes, int slaves,
                SpeedupReport& report) {
  for (int tileSize : tileSizes) report.serial.push_back({tileSize, {}, {}});
  for (Schedule schedule : options.schedules) {
    for (int tileSize : tileSizes) {
      for (int p = 1; p <= slaves; ++p) {
        ScalingPoint point;
        point.schedule = schedule;
        point.tileSize = tileSize;
        point.slaves = p;
        point.threadsPerRank = options.threadsPerRank;
        point.busyFractions.resize(static_cast<size_t>(p));
        // Rank 0 keeps a process running (it coordinates) beside the render threads.
        point.oversubscribed = p * options.threadsPerRank + 1 > report.cores;
        report.points.push_back(point);
      }
    }
  }
}

// Renders every point options.repeats times; returns each tile size's serial tile times.
std::map<int, std::vector<std::vector<double>>> measurePoints(Measurement& measure,
                                                              const SpeedupOptions& options,
                                                              int warmUpTileSize, int slaves,
                                                              SpeedupReport& report) {
  const size_t frames =
      1 + static_cast<size_t>(options.repeats) * (report.serial.size() + report.points.size());
  ProgressBar progress("measuring", frames, "frames", !options.quiet && stderrIsTerminal());
  size_t done = 0;
  // Warm-up, not counted: every slave renders once (caches, lazily built caustic maps).
  measure.parallel(Schedule::Dynamic, warmUpTileSize, slaves);
  progress.update(++done);
  std::map<int, std::vector<std::vector<double>>> serialTiles;  // tile size -> runs
  // Repeats are rounds over every point, so slow drift in the machine's load spreads over
  // all points instead of biasing the ones measured last.
  for (int round = 0; round < options.repeats; ++round) {
    for (SerialPoint& s : report.serial) {
      const FrameResult f = measure.serial(s.tileSize);
      s.samples.push_back(f.seconds);
      serialTiles[s.tileSize].push_back(f.tileSeconds);
      progress.update(++done);
    }
    for (ScalingPoint& p : report.points) {
      const FrameResult f = measure.parallel(p.schedule, p.tileSize, p.slaves);
      p.samples.push_back(f.seconds);
      for (int r = 1; r <= p.slaves; ++r) {
        const RankStats& w = f.workers[r];
        p.busyFractions[r - 1].push_back(w.busySeconds / (std::max(w.threads, 1) * f.seconds));
      }
      progress.update(++done);
    }
  }
  progress.finish();
  return serialTiles;
}

// The statistics, the model fitted to them and the projections to larger images and clusters.
void analyse(const SpeedupOptions& options,
             const std::map<int, std::vector<std::vector<double>>>& serialTiles,
             SpeedupReport& report) {
  deriveStatistics(report);
  std::map<int, std::vector<double>> costsBySize;
  for (const auto& [tileSize, runs] : serialTiles) costsBySize[tileSize] = medianTileSeconds(runs);
  predictMeasuredPoints(report, costsBySize);
  const TileCostMap costs(report.width, report.height,
                          planTiles(report.width, report.height, report.serialTileSize),
                          costsBySize[report.serialTileSize]);
  ProjectionPlan plan;
  plan.sizes = {{report.width, report.height}, {1920, 1080}, {3840, 2160}, {7680, 4320}};
  plan.tileSize = report.serialTileSize;
  plan.maxWorkers = options.projectWorkers;
  plan.schedules = options.schedules;
  report.projection = projectScaling(costs, plan, report);
  ProjectionPlan realtime = plan;
  realtime.sizes = {{report.width, report.height}, {1280, 720}, {1920, 1080}};
  report.frameRates = projectFrameRates(costs, realtime, report);
}

// The whole measurement on a started session.
void measureSpeedup(MasterSession& session, const SpeedupOptions& options,
                    const SpeedupOutputs& files, const ChartWriter& chartWriter,
                    SpeedupReport& report, std::ostream& out, std::ostream& err) {
  session.start();
  waitForSlaves(session.link());
  recordSetUp(session, report);
  const PreparedPass prepared = prepareCaustics(session.dispatcher());
  report.setup.causticStage = prepared.stage;
  report.setup.causticSeconds = prepared.seconds;
  if (prepared.progressiveAsOneFrame) {
    err << "prism: note: a progressive scene is measured as one k-NN photon-map frame\n";
  }
  const int slaves = session.link().ranks() - 1;
  std::vector<int> tileSizes = options.tileSizes;
  if (tileSizes.empty()) {
    tileSizes = {automaticTileSize(report.width, report.height, slaves * options.threadsPerRank)};
  }
  // Bandwidth from messages the size of the largest tile result, and at least 256 kB so
  // that their transfer time stands out of the latency's noise.
  const int largestTile = *std::max_element(tileSizes.begin(), tileSizes.end());
  const size_t probeBytes = std::max<size_t>(
      size_t{256} << 10, static_cast<size_t>(tileResultBytes(largestTile * largestTile)));
  report.link = measureLink(session.link(), probeBytes, options.linkRoundTrips);
  planPoints(options, tileSizes, slaves, report);
  Measurement measure(session.dispatcher(), options, prepared.pass);
  analyse(options, measurePoints(measure, options, tileSizes.front(), slaves, report), report);
  printSpeedupTable(report, out);
  writeOutputs(report, files, chartWriter, out, err);
}

}  // namespace

int runSpeedup(const SpeedupOptions& options, std::ostream& out, std::ostream& err,
               Transport* session, const ChartWriter& chartWriter) {
  if (!session || session->size() < 2) {
    err << "prism: error: prism speedup measures inside one MPI job and needs at least 2 ranks: "
           "rank 0 coordinates and ranks 1..N-1 render, so the job measures 1..N-1 slaves.\n"
           "  Start it as: mpiexec -n N prism speedup "
        << (options.render.scenePath.empty() ? "scene.yaml" : options.render.scenePath)
        << "\n  (add --oversubscribe when N exceeds the cores; see docs/scaling.md)\n";
    return 1;
  }
  SpeedupReport report;
  // First, before the command's own work adds to the process's age.
  report.setup.startSeconds = secondsSinceProcessStart().value_or(-1.0);
  report.setup.launchSeconds = secondsFromParentStart().value_or(-1.0);
  report.setup.mpiInitSeconds = session->setUpSeconds();
  report.scenePath = options.render.scenePath;
  report.ranks = session->size();
  report.cores = machineCores();
  report.threadsPerRank = options.threadsPerRank;
  report.repeats = options.repeats;
  report.prefetch = options.render.distribution.prefetch;
  const SpeedupOutputs files = speedupOutputs(
      options.outputPrefix.empty()
          ? "speedup-" + std::filesystem::path(options.render.scenePath).stem().string()
          : options.outputPrefix);
  MasterSession run(session, options.render, err);
  const auto checkFolder = [&] {
    const std::filesystem::path folder = std::filesystem::path(files.csv).parent_path();
    if (!folder.empty() && !std::filesystem::is_directory(folder)) {
      throw std::runtime_error("output folder " + folder.string() + " does not exist");
    }
  };
  if (!run.load(checkFolder)) return 1;
  return run.runToEnd(
      [&] {
        measureSpeedup(run, options, files, chartWriter, report, out, err);
        return 0;
      },
      out);
}

}  // namespace prism

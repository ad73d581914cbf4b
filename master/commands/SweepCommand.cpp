#include "master/commands/SweepCommand.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <ostream>

#include "image/Thumbnail.h"
#include "master/analysis/SweepReport.h"
#include "master/commands/MasterSession.h"
#include "master/commands/ProgressBar.h"
#include "master/frame/CausticPasses.h"
#include "transport/Transport.h"
#include "util/AtomicFile.h"
#include "util/Parallel.h"
#include "util/Stopwatch.h"
#include "util/ThreadCount.h"

namespace prism {
namespace {

// One timed render: a single point, or a whole progressive family, scored pass by pass.
struct SweepRun {
  std::vector<size_t> rows;  // the rows it measures, in rising value
  bool progressive = false;
};

std::vector<SweepRun> groupRuns(const std::vector<SweepRow>& rows) {
  std::vector<SweepRun> runs;
  for (size_t i = 0; i < rows.size(); ++i) {
    const bool progressive = rows[i].point.family == SweepFamily::Passes;
    if (progressive && !runs.empty() && runs.back().progressive) {
      runs.back().rows.push_back(i);
    } else {
      runs.push_back({{i}, progressive});
    }
  }
  return runs;
}

class Sweep {
 public:
  Sweep(const SweepOptions& options, const SceneDescription& scene, const SweepReference& ref,
        SweepReport& report)
      : options_(options), scene_(scene), ref_(ref), report_(report) {
    regionRect_ = maskBounds(ref.region, ref.image.width, ref.image.height);
  }

  // Renders the run once; the first round also scores its images.
  void execute(const SweepRun& run, bool score) {
    SweepRow& last = report_.rows[run.rows.back()];
    SceneDescription d = scene_;
    d.caustics = last.point.caustics;
    d.render.samplesPerPixel = last.point.samplesPerPixel;
    const Scene scene(d);  // not timed: parsing and the BVH are the same for every method
    FrameOptions frame;
    frame.distribution.threads = options_.render.distribution.threads;
    const double cpuStart = processCpuSeconds();
    const auto start = SteadyClock::now();
    ProgressiveSnapshot snapshot;
    double scoringWall = 0.0, scoringCpu = 0.0;  // spent scoring snapshots: not the method's
    if (run.progressive) {
      snapshot = [&](int passes, const ImageRgb& image) {
        for (const size_t i : run.rows) {
          SweepRow& row = report_.rows[i];
          if (row.point.value != static_cast<uint64_t>(passes)) continue;
          row.seconds.push_back(secondsSince(start) - scoringWall);
          row.cpuSeconds.push_back(processCpuSeconds() - cpuStart - scoringCpu);
          if (!score) continue;
          const double cpuBefore = processCpuSeconds();
          const auto before = SteadyClock::now();
          scoreRow(row, image);
          scoringWall += secondsSince(before);
          scoringCpu += processCpuSeconds() - cpuBefore;
        }
      };
    }
    const CausticFrame result = renderWithCaustics(scene, frame, {}, snapshot);
    if (run.progressive) return;
    last.seconds.push_back(secondsSince(start));
    last.cpuSeconds.push_back(processCpuSeconds() - cpuStart);
    if (score) scoreRow(last, result.image);
  }

 private:
  void scoreRow(SweepRow& row, const ImageRgb& image) {
    const ImageRgb& base = baseFor(row.point.samplesPerPixel);
    row.image = imageError(image, ref_.image, base);
    row.region = imageError(image, ref_.image, base, ref_.region);
    row.thumbnail = thumbnail(image, regionRect_, options_.thumbnailHeight);
  }

  // The frame without caustics at this sample count (the reference's own for its count).
  const ImageRgb& baseFor(int samplesPerPixel) {
    if (samplesPerPixel == scene_.render.samplesPerPixel) return ref_.base;
    auto it = bases_.find(samplesPerPixel);
    if (it == bases_.end()) {
      SceneDescription d = scene_;
      d.render.samplesPerPixel = samplesPerPixel;
      it = bases_
               .emplace(samplesPerPixel,
                        renderWithoutCaustics(d, options_.render.distribution.threads))
               .first;
    }
    return it->second;
  }

  const SweepOptions& options_;
  const SceneDescription& scene_;
  const SweepReference& ref_;
  SweepReport& report_;
  PixelRect regionRect_;
  std::map<int, ImageRgb> bases_;
};

std::string defaultPrefix(const std::string& scenePath) {
  return "sweep-" + std::filesystem::path(scenePath).stem().string();
}

}  // namespace

SweepOutputs sweepOutputs(const std::string& prefix) {
  return {prefix + ".csv", prefix + ".png", prefix + "-reference"};
}

int runSweep(const SweepOptions& options, std::ostream& out, std::ostream& err, Transport* session,
             const ChartWriter& chartWriter) {
  if (session && session->size() > 1) {
    return MasterSession(session, options.render, err)
        .refuse(
            "prism sweep runs in one process on this machine's cores; start it without mpiexec "
            "(it times methods, not the cluster: see prism speedup)");
  }
  try {
    const std::string prefix = options.outputPrefix.empty()
                                   ? defaultPrefix(options.render.scenePath)
                                   : options.outputPrefix;
    const SweepOutputs files = sweepOutputs(prefix);
    const std::filesystem::path folder = std::filesystem::path(files.csv).parent_path();
    if (!folder.empty() && !std::filesystem::is_directory(folder)) {
      throw std::runtime_error("the output folder " + folder.string() + " does not exist");
    }
    const SceneDescription scene = loadSceneWithOverrides(options.render);
    const std::vector<SweepPoint> points = planSweep(options.families, options.values, scene);
    if (points.empty()) throw std::runtime_error("nothing to sweep: no family has a value");

    // One bar per stage before the sweep (reference passes), then one over every run.
    StageProgress bar(!options.quiet);
    ReferenceRequest request = options.reference;
    if (request.cacheStem.empty()) request.cacheStem = files.referenceStem;
    request.threads = options.render.distribution.threads;
    const SweepReference ref = makeSweepReference(scene, request, std::ref(bar));
    bar.finish();

    SweepReport report;
    report.scenePath = options.render.scenePath;
    report.width = scene.render.width;
    report.height = scene.render.height;
    report.samplesPerPixel = scene.render.samplesPerPixel;
    report.cores = availableCores();
    report.threads = ThreadCount::resolve(options.render.distribution.threads).value();
    report.repeats = options.repeats;
    report.cpuAxis = options.cpuAxis;
    report.metric = options.metric;
    report.exposure = scene.render.exposure;
    report.referenceKind = ref.kind;
    report.referenceDescription = ref.description;
    report.referenceCached = ref.cached;
    report.regionPixels = maskedPixels(ref.region);
    report.convergence = ref.convergence;
    report.plannedPoints = points.size();
    const PixelRect rect = maskBounds(ref.region, ref.image.width, ref.image.height);
    report.referenceThumbnail = thumbnail(ref.image, rect, options.thumbnailHeight);
    report.baseThumbnail = thumbnail(ref.base, rect, options.thumbnailHeight);
    if (report.regionPixels == 0) {
      err << "prism: warning: the reference has no caustic light, so the caustic-region "
             "numbers are empty; the whole-frame numbers are charted instead\n";
    }
    for (const SweepPoint& p : points) report.rows.push_back({p, {}, {}, {}, {}, false, {}});

    const std::vector<SweepRun> runs = groupRuns(report.rows);
    ProgressBar progress("sweep", runs.size() * static_cast<size_t>(options.repeats), "renders",
                         !options.quiet);
    Sweep sweep(options, scene, ref, report);
    const auto start = SteadyClock::now();
    size_t done = 0;
    for (int round = 0; round < options.repeats && !report.budgetHit; ++round) {
      for (const SweepRun& run : runs) {
        if (options.budgetSeconds > 0.0 && secondsSince(start) >= options.budgetSeconds) {
          report.budgetHit = true;
          break;
        }
        sweep.execute(run, round == 0);
        progress.update(++done);
      }
    }
    progress.finish();
    report.rows.erase(std::remove_if(report.rows.begin(), report.rows.end(),
                                     [](const SweepRow& r) { return r.seconds.empty(); }),
                      report.rows.end());
    markParetoFront(report);

    writeFileAtomically(files.csv, [&](std::ostream& f) { writeSweepCsv(report, f); });
    if (!options.quiet) printSweepTable(report, out);
    out << "wrote " << files.csv;
    if (chartWriter) {
      chartWriter(sweepChart(report), files.chart);
      out << " and " << files.chart;
    }
    out << "\n";
    if (!chartWriter) {
      err << "prism: note: the chart needs Qt5 Charts, which this build lacks; the CSV holds "
             "every number\n";
    }
  } catch (const std::exception& e) {
    err << "prism: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace prism

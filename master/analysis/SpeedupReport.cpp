#include "master/analysis/SpeedupReport.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <ostream>
#include <stdexcept>

#include "master/analysis/NumberText.h"
#include "master/analysis/ScalingProjection.h"
#include "master/dispatch/ScheduleNames.h"

namespace prism {
namespace {

// How rank 0 waits for messages (docs/distributed.md, "Waiting for messages").
const char* linkWaits(const LinkMeasurement& link) {
  return link.wakesOnMessage ? "waits woken by the sender (and a probe every 1 ms)"
                             : "waits probe every 1 ms";
}

std::string joinBusy(const std::vector<double>& busy, const char* separator, double scale,
                     const char* pattern) {
  std::string text;
  for (size_t i = 0; i < busy.size(); ++i) {
    if (i > 0) text += separator;
    text += formatNumber(pattern, busy[i] * scale);
  }
  return text;
}

double meanOf(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

}  // namespace

const char* scheduleName(Schedule schedule) {
  return kScheduleNames.nameOf(schedule).data();  // the table's names are string literals
}

std::string ScalingPoint::series() const {
  return std::string(scheduleName(schedule)) + "-" + std::to_string(tileSize);
}

double SpeedupReport::modelError(bool includeOversubscribed) const {
  double sum = 0.0;
  int count = 0;
  for (const ScalingPoint& p : points) {
    if (!std::isfinite(p.modelSeconds) || (p.oversubscribed && !includeOversubscribed)) continue;
    sum += std::abs(p.modelSeconds - p.seconds.median) / p.seconds.median;
    ++count;
  }
  return count > 0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
}

void deriveStatistics(SpeedupReport& report) {
  if (report.serial.empty()) throw std::invalid_argument("no serial run to compare with");
  report.serialSeconds = std::numeric_limits<double>::infinity();
  for (SerialPoint& s : report.serial) {
    s.seconds = spreadOf(s.samples);
    if (s.seconds.median < report.serialSeconds) {
      report.serialSeconds = s.seconds.median;
      report.serialTileSize = s.tileSize;
    }
  }
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> series;
  for (ScalingPoint& p : report.points) {
    p.seconds = spreadOf(p.samples);
    p.speedup = speedupOf(report.serialSeconds, p.seconds.median);
    p.efficiency = efficiencyOf(p.speedup, p.workers());
    p.karpFlatt = karpFlattOf(p.speedup, p.workers());
    p.workerBusy.clear();
    for (const std::vector<double>& busy : p.busyFractions) {
      p.workerBusy.push_back(busy.empty() ? 0.0 : spreadOf(busy).median);
    }
    auto& [workers, speedups] = series[p.series()];
    workers.push_back(p.workers());
    speedups.push_back(p.speedup);
  }
  for (ScalingPoint& p : report.points) {
    const auto& [workers, speedups] = series[p.series()];
    p.amdahlFraction = fitAmdahl(workers, speedups).serialFraction;
    p.amdahlSpeedup = amdahlSpeedup(p.amdahlFraction, p.workers());
  }
}

const std::vector<std::string>& speedupCsvColumns() {
  static const std::vector<std::string> columns{
      "series",     "schedule",       "tile_size",     "slaves",      "threads_per_rank",
      "p",          "seconds",        "seconds_min",   "seconds_max", "speedup",
      "efficiency", "karp_flatt",     "busy_mean",     "busy_min",    "worker_busy",
      "amdahl_f",   "amdahl_speedup", "model_seconds", "model_error", "oversubscribed"};
  return columns;
}

void writeSpeedupCsv(const SpeedupReport& r, std::ostream& out) {
  out << "# prism speedup: " << r.scenePath << ", " << r.width << "x" << r.height << ", "
      << r.samplesPerPixel << " spp; " << r.ranks << " MPI ranks (rank 0 coordinates), "
      << r.threadsPerRank << " thread(s) per slave, " << r.cores << " cores; medians of "
      << r.repeats << " runs\n";
  out << "# kernels: " << r.instructionSet << "\n";
  out << "# T1 = " << formatNumber("%.6g", r.serialSeconds)
      << " s: 1 process, 1 thread, no MPI, tile " << r.serialTileSize
      << "; p = slaves x threads per slave; set-up not in seconds\n";
  const SpeedupSetup& s = r.setup;
  out << "# set-up (s): launch " << formatNumber("%.3f", s.launchSeconds) << ", start "
      << formatNumber("%.3f", s.startSeconds) << ", mpi_init "
      << formatNumber("%.3f", s.mpiInitSeconds) << ", parse "
      << formatNumber("%.3f", s.parseSeconds) << ", broadcast "
      << formatNumber("%.3f", s.broadcastSeconds) << ", build "
      << formatNumber("%.3f", s.buildSeconds) << ", slowest slave build "
      << formatNumber("%.3f", s.slaveBuildSeconds) << ", slowest slave start "
      << formatNumber("%.3f", s.slaveStartSeconds) << ", slowest slave mpi_init "
      << formatNumber("%.3f", s.slaveMpiInitSeconds) << " (-1: not known)\n";
  out << "# link: latency " << formatNumber("%.3g", r.link.model.latencySeconds * 1e3)
      << " ms one way, bandwidth " << formatNumber("%.3g", r.link.model.bytesPerSecond / 1e6)
      << " MB/s, " << linkWaits(r.link) << "\n";
  const std::vector<std::string>& columns = speedupCsvColumns();
  for (size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
  out << "\n";
  for (const ScalingPoint& p : r.points) {
    const double busyMin =
        p.workerBusy.empty() ? 0.0 : *std::min_element(p.workerBusy.begin(), p.workerBusy.end());
    const double modelError = (p.modelSeconds - p.seconds.median) / p.seconds.median;
    out << p.series() << "," << scheduleName(p.schedule) << "," << p.tileSize << "," << p.slaves
        << "," << p.threadsPerRank << "," << p.workers() << "," << csvNumber(p.seconds.median)
        << "," << csvNumber(p.seconds.min) << "," << csvNumber(p.seconds.max) << ","
        << csvNumber(p.speedup) << "," << csvNumber(p.efficiency) << "," << csvNumber(p.karpFlatt)
        << "," << csvNumber(meanOf(p.workerBusy), "%.4f") << "," << csvNumber(busyMin, "%.4f")
        << "," << joinBusy(p.workerBusy, ";", 1.0, "%.4f") << "," << csvNumber(p.amdahlFraction)
        << "," << csvNumber(p.amdahlSpeedup) << "," << csvNumber(p.modelSeconds) << ","
        << csvNumber(modelError, "%.4f") << "," << (p.oversubscribed ? "yes" : "no") << "\n";
  }
}

void writeProjectionCsv(const SpeedupReport& r, std::ostream& out) {
  out << "# prism speedup projection: " << r.scenePath
      << "; simulated pull queue replaying the measured tile costs and link; "
         "one core per render thread; model error on the measured points "
      << formatNumber("%.1f", r.modelError(false) * 100) << "% (not oversubscribed)\n";
  out << "width,height,tile_size,schedule,p,seconds,serial_seconds,speedup,efficiency\n";
  for (const ProjectedPoint& p : r.projection) {
    out << p.width << "," << p.height << "," << p.tileSize << "," << scheduleName(p.schedule) << ","
        << p.workers << "," << csvNumber(p.seconds) << "," << csvNumber(p.serialSeconds) << ","
        << csvNumber(p.speedup()) << "," << csvNumber(p.speedup() / p.workers) << "\n";
  }
}

namespace {

// Projected points as a table: a row per worker count, a column per image size (each in their
// order), a cell from the point `cell` returns text for ("-" where none does).
template <class Point, class Cell>
void printSizeTable(const std::vector<Point>& points, int cellWidth, Cell cell, std::ostream& out) {
  std::vector<std::pair<int, int>> sizes;
  std::vector<int> workers;
  for (const Point& p : points) {
    if (std::find(sizes.begin(), sizes.end(), std::pair{p.width, p.height}) == sizes.end())
      sizes.push_back({p.width, p.height});
    if (std::find(workers.begin(), workers.end(), p.workers) == workers.end())
      workers.push_back(p.workers);
  }
  char line[160];
  std::snprintf(line, sizeof line, "  %8s", "p");
  out << line;
  for (const auto& [w, h] : sizes) {
    std::snprintf(line, sizeof line, " %*s", cellWidth,
                  (std::to_string(w) + "x" + std::to_string(h)).c_str());
    out << line;
  }
  out << "\n";
  for (int p : workers) {
    std::snprintf(line, sizeof line, "  %8d", p);
    out << line;
    for (const auto& [w, h] : sizes) {
      std::string text = "-";
      for (const Point& q : points) {
        if (q.workers != p || q.width != w || q.height != h) continue;
        if (const std::optional<std::string> t = cell(q)) text = *t;
      }
      std::snprintf(line, sizeof line, " %*s", cellWidth, text.c_str());
      out << line;
    }
    out << "\n";
  }
}

// The viewer's projected real-time frame rates: one row per worker count, one column per size,
// "pipelined (unpipelined)" frames/s; then what the largest size's stream puts on the link.
void printFrameRates(const SpeedupReport& r, std::ostream& out) {
  if (r.frameRates.empty()) return;
  out << "\n  real time (simulated 1-spp frames at full resolution, frames/s pipelined "
         "(unpipelined), the measured link):\n";
  printSizeTable(
      r.frameRates, 18,
      [](const FrameRatePoint& q) -> std::optional<std::string> {
        return formatNumber("%.1f", q.framesPerSecond) + " (" +
               formatNumber("%.1f", q.unpipelinedFramesPerSecond) + ")";
      },
      out);
  char line[160];
  const FrameRatePoint& largest = r.frameRates.back();
  const int w = largest.width, h = largest.height;
  const double bytesAt30 = streamBytesPerSecond(w, h, r.serialTileSize, 30.0);
  std::snprintf(line, sizeof line,
                "  a %dx%d stream at 30 frames/s sends %.0f MB/s of tile results to rank 0 "
                "(%.1f Gbit/s), measured link: %.0f MB/s\n",
                w, h, bytesAt30 / 1e6, bytesAt30 * 8 / 1e9, r.link.model.bytesPerSecond / 1e6);
  out << line;
}

}  // namespace

void printSpeedupTable(const SpeedupReport& r, std::ostream& out) {
  char line[512];
  out << "\nprism speedup: " << r.scenePath << ", " << r.width << "x" << r.height << ", "
      << r.samplesPerPixel << " spp\n";
  out << "  job: " << r.ranks << " ranks (rank 0 coordinates, " << r.ranks - 1 << " slaves x "
      << r.threadsPerRank << " thread(s)) on " << r.cores << " cores; every time is the median of "
      << r.repeats << " runs [min-max]\n";
  out << "  kernels: " << r.instructionSet << "\n";
  const SpeedupSetup& s = r.setup;
  if (s.startSeconds >= 0.0) {
    out << "  start (rank 0, before the command): ";
    if (s.launchSeconds >= 0.0) {
      out << "launch " << formatNumber("%.3f", s.launchSeconds)
          << " s (its parent's start to its own), ";
    }
    out << "process start to command " << formatNumber("%.3f", s.startSeconds)
        << " s, of which MPI_Init " << formatNumber("%.3f", s.mpiInitSeconds) << " s\n";
  }
  if (s.slaveStartSeconds >= 0.0) {
    out << "  start (slowest slave, before its command): process start to command "
        << formatNumber("%.3f", s.slaveStartSeconds) << " s, MPI_Init "
        << formatNumber("%.3f", s.slaveMpiInitSeconds) << " s\n";
  }
  std::snprintf(line, sizeof line,
                "  set-up (not in the frame times): parse %.3f s, broadcast %.3f s (%zu bytes), "
                "build %.3f s (slowest slave %.3f s)",
                s.parseSeconds, s.broadcastSeconds, s.broadcastBytes, s.buildSeconds,
                s.slaveBuildSeconds);
  out << line;
  if (!s.causticStage.empty())
    out << ", " << s.causticStage << " " << formatNumber("%.3f", s.causticSeconds) << " s";
  out << "\n";
  std::snprintf(line, sizeof line,
                "  link (Echo through the transport, %d round trips per size and slave): latency "
                "%.3f ms one way, bandwidth %.1f MB/s (%zu-byte messages); %s\n",
                r.link.roundTrips, r.link.model.latencySeconds * 1e3,
                r.link.model.bytesPerSecond / 1e6, r.link.largeBytes, linkWaits(r.link));
  out << line;
  out << "  T1 (1 process, 1 thread, no MPI):";
  for (const SerialPoint& p : r.serial) {
    std::snprintf(line, sizeof line, " tile %d: %.3f s [%.3f-%.3f];", p.tileSize, p.seconds.median,
                  p.seconds.min, p.seconds.max);
    out << line;
  }
  out << " T1 = " << formatNumber("%.3f", r.serialSeconds) << " s\n\n";
  std::snprintf(line, sizeof line, "  %-8s %5s %5s %22s %7s %6s %7s %7s %8s  %s\n", "schedule",
                "tile", "p", "frame s [min-max]", "S", "E", "K-F e", "model s", "model err",
                "busy % per slave");
  out << line;
  for (const ScalingPoint& p : r.points) {
    char time[64];
    std::snprintf(time, sizeof time, "%.3f [%.3f-%.3f]", p.seconds.median, p.seconds.min,
                  p.seconds.max);
    const std::string kf = std::isfinite(p.karpFlatt) ? formatNumber("%.3f", p.karpFlatt) : "-";
    const std::string model =
        std::isfinite(p.modelSeconds) ? formatNumber("%.3f", p.modelSeconds) : "-";
    const std::string error =
        std::isfinite(p.modelSeconds)
            ? formatNumber("%+.1f%%", (p.modelSeconds - p.seconds.median) / p.seconds.median * 100)
            : "-";
    std::snprintf(line, sizeof line, "  %-8s %5d %5d %22s %7.3f %6.3f %7s %7s %8s  %s%s\n",
                  scheduleName(p.schedule), p.tileSize, p.workers(), time, p.speedup, p.efficiency,
                  kf.c_str(), model.c_str(), error.c_str(),
                  joinBusy(p.workerBusy, " ", 100.0, "%.0f").c_str(),
                  p.oversubscribed ? "  oversubscribed" : "");
    out << line;
  }
  out << "  S = T1/Tp; E = S/p; K-F e = Karp-Flatt serial fraction (1/S - 1/p)/(1 - 1/p); model: "
         "simulated frame time;\n  busy: each active slave's rendering time over its threads x "
         "the frame time; oversubscribed: p + rank 0 > cores\n";
  out << "\n  Amdahl fit (least squares on 1/S), per series:";
  std::vector<std::string> seen;
  for (const ScalingPoint& p : r.points) {
    if (std::find(seen.begin(), seen.end(), p.series()) != seen.end()) continue;
    seen.push_back(p.series());
    out << " " << p.series() << " f = " << formatNumber("%.3f", p.amdahlFraction);
  }
  out << "\n";
  std::snprintf(line, sizeof line,
                "  model error (mean |model - measured| / measured): %.1f%% not oversubscribed, "
                "%.1f%% all points\n",
                r.modelError(false) * 100, r.modelError(true) * 100);
  out << line;
  if (!r.projection.empty()) {
    out << "\n  projection (simulated, one core per render thread; speedup S for p workers):\n";
    printSizeTable(
        r.projection, 12,
        [](const ProjectedPoint& q) -> std::optional<std::string> {
          if (q.schedule != Schedule::Dynamic) return std::nullopt;
          return formatNumber("%.1f", q.speedup());
        },
        out);
  }
  printFrameRates(r, out);
}

}  // namespace prism

#include "master/analysis/SweepReport.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>

#include "master/analysis/NumberText.h"
#include "master/analysis/ParetoFront.h"

namespace prism {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double minimum(const std::vector<double>& v) {
  return v.empty() ? std::numeric_limits<double>::quiet_NaN()
                   : *std::min_element(v.begin(), v.end());
}

double maximum(const std::vector<double>& v) {
  return v.empty() ? std::numeric_limits<double>::quiet_NaN()
                   : *std::max_element(v.begin(), v.end());
}

// "25k", "1.6M": photon counts in captions.
std::string shortCount(uint64_t n) {
  if (n >= 1000000) return formatNumber("%gM", static_cast<double>(n) / 1e6);
  if (n >= 10000) return formatNumber("%gk", static_cast<double>(n) / 1e3);
  return std::to_string(n);
}

std::string valueText(const SweepPoint& p) {
  switch (p.family) {
    case SweepFamily::Photons:
      return shortCount(p.value) + " photons";
    case SweepFamily::Gather:
      return "k = " + std::to_string(p.value);
    case SweepFamily::AutoGather:
      return "k <= " + std::to_string(p.value) + " auto";
    case SweepFamily::Passes:
      return std::to_string(p.value) + (p.value == 1 ? " pass" : " passes");
    case SweepFamily::Resolution:
      return std::to_string(p.value) + "x" + std::to_string(p.value);
    case SweepFamily::Steps:
      return std::to_string(p.value) + " steps";
    case SweepFamily::Blur:
      return "blur " + std::to_string(p.value);
    case SweepFamily::Samples:
      return std::to_string(p.value) + " spp";
  }
  return std::to_string(p.value);
}

// "photon map: photons", the name of a family's curve.
std::string curveName(SweepFamily f) {
  return std::string(familyMethod(f)) + ": " + familyName(f);
}

}  // namespace

double SweepRow::medianSeconds() const {
  return median(seconds);
}

double SweepRow::medianCpuSeconds() const {
  return median(cpuSeconds);
}

const char* metricName(SweepMetric metric) {
  switch (metric) {
    case SweepMetric::Mrse:
      return "MRSE";
    case SweepMetric::RelRmse:
      return "relative RMSE";
    case SweepMetric::Rmse:
      return "RMSE";
    case SweepMetric::MaxError:
      return "max error";
  }
  return "?";
}

double SweepRow::error(SweepMetric metric) const {
  const auto pick = [metric](const ImageError& e) {
    switch (metric) {
      case SweepMetric::Mrse:
        return e.mrse;
      case SweepMetric::RelRmse:
        return e.relRmse;
      case SweepMetric::Rmse:
        return e.rmse;
      case SweepMetric::MaxError:
        return e.maxError;
    }
    return e.mrse;
  };
  return region.pixels > 0 ? pick(region) : pick(image);
}

void markParetoFront(SweepReport& report) {
  std::vector<double> cost, error;
  for (const SweepRow& r : report.rows) {
    cost.push_back(r.cost(report.cpuAxis));
    error.push_back(r.error(report.metric));
  }
  const std::vector<bool> front = paretoFront(cost, error);
  for (size_t i = 0; i < report.rows.size(); ++i) report.rows[i].pareto = front[i];
}

const std::vector<std::string>& sweepCsvColumns() {
  static const std::vector<std::string> columns{"family",
                                                "method",
                                                "value",
                                                "photons",
                                                "k",
                                                "passes",
                                                "map_resolution",
                                                "map_steps",
                                                "map_blur_radius",
                                                "spp",
                                                "runs",
                                                "seconds_median",
                                                "seconds_min",
                                                "seconds_max",
                                                "cpu_seconds_median",
                                                "rmse",
                                                "rel_rmse",
                                                "mrse",
                                                "max_error",
                                                "flux_ratio",
                                                "region_pixels",
                                                "region_rmse",
                                                "region_rel_rmse",
                                                "region_mrse",
                                                "region_max_error",
                                                "region_flux_ratio",
                                                "pareto",
                                                "reference"};
  return columns;
}

void writeSweepCsv(const SweepReport& report, std::ostream& out) {
  const auto& columns = sweepCsvColumns();
  for (size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
  out << "\n";
  for (const SweepRow& r : report.rows) {
    const CausticSettings& c = r.point.caustics;
    const bool photonMap = c.method == CausticMethod::PhotonMap;
    const bool causticMap = c.method == CausticMethod::CausticMap;
    const auto onlyIf = [](bool used, auto value) {
      return used ? std::to_string(value) : std::string();
    };
    out << familyName(r.point.family) << "," << familyMethod(r.point.family) << "," << r.point.value
        << "," << onlyIf(photonMap, c.photons) << ","
        << onlyIf(photonMap && !c.progressive, c.gather) << ","
        << onlyIf(photonMap && c.progressive, c.passes) << ","
        << onlyIf(causticMap, c.mapResolution) << "," << onlyIf(causticMap, c.mapSteps) << ","
        << onlyIf(causticMap, c.mapBlurRadius) << "," << r.point.samplesPerPixel << ","
        << r.seconds.size() << "," << csvNumber(r.medianSeconds()) << ","
        << csvNumber(minimum(r.seconds)) << "," << csvNumber(maximum(r.seconds)) << ","
        << csvNumber(r.medianCpuSeconds()) << "," << csvNumber(r.image.rmse) << ","
        << csvNumber(r.image.relRmse) << "," << csvNumber(r.image.mrse) << ","
        << csvNumber(r.image.maxError) << "," << csvNumber(r.image.fluxRatio) << ","
        << r.region.pixels << "," << csvNumber(r.region.rmse) << "," << csvNumber(r.region.relRmse)
        << "," << csvNumber(r.region.mrse) << "," << csvNumber(r.region.maxError) << ","
        << csvNumber(r.region.fluxRatio) << "," << (r.pareto ? "yes" : "no") << ","
        << report.referenceKind << "\n";
  }
}

void printSweepTable(const SweepReport& report, std::ostream& out) {
  out << "reference: " << report.referenceDescription << (report.referenceCached ? " [cached]" : "")
      << "\n";
  for (const ReferenceConvergence& c : report.convergence) {
    out << "  after " << c.passes << " passes" << formatNumber(" (%7.1f s)", c.seconds)
        << ": relative RMSE against the final image " << formatNumber("%.4f", c.regionRelRmse)
        << " in the caustic region, " << formatNumber("%.4f", c.imageRelRmse) << " whole frame\n";
  }
  out << "caustic region: " << report.regionPixels << " pixels\n";
  out << "method                  family     value      " << (report.cpuAxis ? "cpu s " : "wall s")
      << "  (min..max)        rel RMSE region  "
         "rel RMSE image  MRSE region  max err  flux   front\n";
  for (const SweepRow& r : report.rows) {
    char line[400];
    std::snprintf(
        line, sizeof line,
        "%-23s %-10s %-10s %7.3f (%.3f..%.3f)  %15.4f %15.4f %12.4g %8.3g %6.3f  %s\n",
        familyMethod(r.point.family), familyName(r.point.family), valueText(r.point).c_str(),
        r.cost(report.cpuAxis), report.cpuAxis ? minimum(r.cpuSeconds) : minimum(r.seconds),
        report.cpuAxis ? maximum(r.cpuSeconds) : maximum(r.seconds), r.region.relRmse,
        r.image.relRmse, r.region.mrse, r.image.maxError, r.region.fluxRatio, r.pareto ? "*" : "");
    out << line;
  }
  if (report.budgetHit) {
    out << "budget reached: " << report.rows.size() << " of " << report.plannedPoints
        << " points measured\n";
  }
}

Chart sweepChart(const SweepReport& report) {
  Chart chart;
  chart.title = "prism sweep: " + report.scenePath;
  chart.note = std::to_string(report.width) + "x" + std::to_string(report.height) + ", " +
               std::to_string(report.samplesPerPixel) + " spp, " + std::to_string(report.threads) +
               " threads on " + std::to_string(report.cores) + " cores; " +
               (report.cpuAxis ? "CPU" : "wall") + " seconds, median of up to " +
               std::to_string(report.repeats) + " runs. Reference: " + report.referenceDescription +
               (report.referenceCached ? " [cached]" : "");
  if (!report.convergence.empty()) {
    const ReferenceConvergence& half = report.convergence.back();
    chart.note +=
        formatNumber("; after half its passes it was still %.2f %%", 100.0 * half.regionRelRmse) +
        " (relative RMSE, caustic region) from its final image";
  }
  chart.note += ". Caustic region: " + std::to_string(report.regionPixels) + " pixels.";
  if (report.budgetHit) {
    chart.note += " Budget reached: " + std::to_string(report.rows.size()) + " of " +
                  std::to_string(report.plannedPoints) + " points.";
  }
  const std::string time = report.cpuAxis ? "CPU seconds" : "seconds";
  const std::string where = report.regionPixels > 0 ? "caustic region" : "whole frame";
  ChartPanel error{"Error against time (" + where + ")",
                   time,
                   metricName(report.metric),
                   true,
                   true,
                   {},
                   10.0,
                   ""};
  ChartPanel flux{"Caustic flux found (" + where + ")",
                  time,
                  "flux ratio (1 = all of the reference's)",
                  true,
                  false,
                  {},
                  10.0,
                  ""};
  ChartSeries front{"Pareto front", ChartSeries::Kind::Front, {}, {}, {}};
  std::vector<std::pair<double, double>> frontPoints;
  for (const SweepRow& r : report.rows) {
    const std::string name = curveName(r.point.family);
    auto it = std::find_if(error.series.begin(), error.series.end(),
                           [&](const ChartSeries& s) { return s.name == name; });
    if (it == error.series.end()) {
      error.series.push_back({name, ChartSeries::Kind::Measured, {}, {}, {}});
      flux.series.push_back({name, ChartSeries::Kind::Measured, {}, {}, {}});
      it = error.series.end() - 1;
    }
    ChartSeries& f = flux.series[static_cast<size_t>(it - error.series.begin())];
    it->x.push_back(r.cost(report.cpuAxis));
    it->y.push_back(r.error(report.metric));
    f.x.push_back(r.cost(report.cpuAxis));
    f.y.push_back(std::isfinite(r.region.fluxRatio) ? r.region.fluxRatio : r.image.fluxRatio);
    if (r.pareto) frontPoints.emplace_back(r.cost(report.cpuAxis), r.error(report.metric));
  }
  std::sort(frontPoints.begin(), frontPoints.end());
  for (const auto& [x, y] : frontPoints) {
    front.x.push_back(x);
    front.y.push_back(y);
  }
  if (!front.x.empty()) error.series.push_back(front);
  chart.panels = {error, flux};

  ThumbnailStrip reference{
      "reference (" + report.referenceKind +
          ") and the frame without "
          "caustics",
      report.exposure,
      {{report.referenceThumbnail, "reference"}, {report.baseThumbnail, "no caustics"}}};
  chart.strips.push_back(reference);
  for (const SweepRow& r : report.rows) {
    const std::string name = curveName(r.point.family);
    if (chart.strips.back().title != name) chart.strips.push_back({name, report.exposure, {}});
    chart.strips.back().thumbnails.push_back(
        {r.thumbnail, valueText(r.point) + formatNumber("\n%.3g s", r.cost(report.cpuAxis)) +
                          formatNumber(", err %.3g", r.error(report.metric))});
  }
  return chart;
}

}  // namespace prism

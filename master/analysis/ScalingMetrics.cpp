#include "master/analysis/ScalingMetrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace prism {

TimingSpread spreadOf(std::vector<double> samples) {
  if (samples.empty()) throw std::invalid_argument("spreadOf: no samples");
  std::sort(samples.begin(), samples.end());
  const size_t n = samples.size();
  const double median = n % 2 == 1 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  return {median, samples.front(), samples.back()};
}

double speedupOf(double serialSeconds, double parallelSeconds) {
  return serialSeconds / parallelSeconds;
}

double efficiencyOf(double speedup, double workers) {
  return speedup / workers;
}

double karpFlattOf(double speedup, double workers) {
  if (workers <= 1.0) return std::numeric_limits<double>::quiet_NaN();
  return (1.0 / speedup - 1.0 / workers) / (1.0 - 1.0 / workers);
}

double amdahlSpeedup(double serialFraction, double workers) {
  return 1.0 / (serialFraction + (1.0 - serialFraction) / workers);
}

AmdahlFit fitAmdahl(const std::vector<double>& workers, const std::vector<double>& speedups) {
  if (workers.size() != speedups.size()) {
    throw std::invalid_argument("fitAmdahl: as many speedups as worker counts needed");
  }
  double sxy = 0.0, sxx = 0.0;
  for (size_t i = 0; i < workers.size(); ++i) {
    const double x = 1.0 - 1.0 / workers[i];
    const double y = 1.0 / speedups[i] - 1.0 / workers[i];
    sxy += x * y;
    sxx += x * x;
  }
  AmdahlFit fit;
  fit.serialFraction = sxx > 0.0 ? std::clamp(sxy / sxx, 0.0, 1.0) : 0.0;
  double squares = 0.0;
  for (size_t i = 0; i < workers.size(); ++i) {
    const double error = amdahlSpeedup(fit.serialFraction, workers[i]) - speedups[i];
    squares += error * error;
  }
  fit.rmsError = workers.empty() ? 0.0 : std::sqrt(squares / static_cast<double>(workers.size()));
  return fit;
}

}  // namespace prism

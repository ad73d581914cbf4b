// Strong-scaling arithmetic for `prism speedup`: medians with their spread, speedup,
// efficiency, the Karp–Flatt serial fraction and an Amdahl fit. Pure functions, no timing.
#pragma once

#include <vector>

namespace prism {

// Repeated timings of one measurement point.
struct TimingSpread {
  double median = 0.0;
  double min = 0.0;
  double max = 0.0;
};

// Throws std::invalid_argument when samples is empty. An even count gives the mean of the two
// middle values.
TimingSpread spreadOf(std::vector<double> samples);

// S = T1 / Tp.
double speedupOf(double serialSeconds, double parallelSeconds);
// E = S / p.
double efficiencyOf(double speedup, double workers);
// Karp & Flatt (1990): the experimentally determined serial fraction
// e = (1/S − 1/p) / (1 − 1/p); undefined (NaN) for p ≤ 1.
double karpFlattOf(double speedup, double workers);

// Amdahl's law, S(p) = 1 / (f + (1 − f)/p).
double amdahlSpeedup(double serialFraction, double workers);

struct AmdahlFit {
  double serialFraction = 0.0;  // f, in [0, 1]
  double rmsError = 0.0;        // of the fitted speedups against the measured ones
};

// Least squares in the time domain, 1/S = 1/p + f·(1 − 1/p), which is linear in f, so the fit is
// closed-form: f = Σxy / Σx² with x = 1 − 1/p, y = 1/S − 1/p; clamped to [0, 1]. Points with
// p = 1 carry no information about f and add nothing. Throws when the sizes differ.
AmdahlFit fitAmdahl(const std::vector<double>& workers, const std::vector<double>& speedups);

}  // namespace prism

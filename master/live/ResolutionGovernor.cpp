#include "master/live/ResolutionGovernor.h"

#include <algorithm>

#include "util/Percentile.h"

namespace prism {
namespace {

// Two frame sizes closer than this tell the fixed cost apart from the per-sample one too poorly.
constexpr double kMinSizeRatio = 1.2;
// The fixed cost is never taken as more than this share of a measured frame.
constexpr double kMaxFixedShare = 0.9;

}  // namespace

ResolutionGovernor::ResolutionGovernor(double targetSeconds, int maxScale)
    : target_(targetSeconds), ladder_(frameScaleLadder(maxScale)) {}

double ResolutionGovernor::medianSecondsOf(uint64_t samples) const {
  std::vector<double> seconds;
  for (const Frame& f : frames_) {
    if (f.samples == samples) seconds.push_back(f.seconds);
  }
  // The median: one frame slowed by the machine (or a burst of messages) moves it little.
  return seconds.empty() ? 0.0 : percentile(seconds, 0.5);
}

void ResolutionGovernor::frameFinished(uint64_t samples, double seconds) {
  if (samples == 0 || !(seconds > 0.0)) return;
  frames_.push_back({samples, seconds});
  if (frames_.size() > kWindow) frames_.pop_front();
  const auto [smallest, largest] =
      std::minmax_element(frames_.begin(), frames_.end(),
                          [](const Frame& a, const Frame& b) { return a.samples < b.samples; });
  const double small = static_cast<double>(smallest->samples);
  const double large = static_cast<double>(largest->samples);
  if (large < kMinSizeRatio * small) return;  // one size (or nearly): keep the last estimate
  const double tSmall = medianSecondsOf(smallest->samples);
  const double tLarge = medianSecondsOf(largest->samples);
  const double intercept = (tSmall * large - tLarge * small) / (large - small);
  fixed_ = std::clamp(intercept, 0.0, kMaxFixedShare * std::min(tSmall, tLarge));
}

double ResolutionGovernor::predictSeconds(uint64_t samples) const {
  if (frames_.empty()) return 0.0;
  const double measured = medianSecondsOf(samples);
  if (measured > 0.0) return measured;
  const uint64_t reference = frames_.back().samples;
  const double t = medianSecondsOf(reference);
  const double fixed = std::min(fixed_, kMaxFixedShare * t);
  return fixed + (t - fixed) * static_cast<double>(samples) / static_cast<double>(reference);
}

FrameScale ResolutionGovernor::scaleFor(int width, int height) const {
  if (!(target_ > 0.0)) return {};
  if (frames_.empty()) return ladder_.back();
  for (const FrameScale& scale : ladder_) {
    const uint64_t samples =
        static_cast<uint64_t>(scale.side(width)) * static_cast<uint64_t>(scale.side(height));
    if (predictSeconds(samples) <= target_) return scale;
  }
  return ladder_.back();
}

}  // namespace prism

#include "master/ResolutionGovernor.h"

#include <algorithm>

#include "util/Percentile.h"

namespace prism {

ResolutionGovernor::ResolutionGovernor(double targetSeconds, int maxScale)
    : target_(targetSeconds), maxScale_(std::max(maxScale, 1)) {}

void ResolutionGovernor::frameFinished(uint64_t samples, double seconds) {
  if (samples == 0 || !(seconds > 0.0)) return;
  rates_.push_back(static_cast<double>(samples) / seconds);
  if (rates_.size() > kWindow) rates_.pop_front();
}

double ResolutionGovernor::samplesPerSecond() const {
  if (rates_.empty()) return 0.0;
  // The median: one frame slowed by the machine (or a burst of messages) moves it little.
  return percentile({rates_.begin(), rates_.end()}, 0.5);
}

int ResolutionGovernor::scaleFor(int width, int height) const {
  if (!(target_ > 0.0)) return 1;
  const double rate = samplesPerSecond();
  if (!(rate > 0.0)) return maxScale_;
  for (int scale = 1; scale < maxScale_; ++scale) {
    const double pixels = static_cast<double>(std::max(1, width / scale)) *
                          static_cast<double>(std::max(1, height / scale));
    if (pixels / rate <= target_) return scale;
  }
  return maxScale_;
}

}  // namespace prism

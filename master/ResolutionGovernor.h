// Chooses the resolution of the viewer's frames while the camera moves: full resolution when a
// frame is predicted to fit the frame-time target, else each side divided by the smallest
// scale that fits, up to maxScale. The prediction is the frame's samples over the render rate
// (samples per second) of the last frames, so the resolution drops only when a frame would
// miss the target and comes back as soon as one fits. Pure bookkeeping (times are passed in),
// tested without threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>

namespace prism {

class ResolutionGovernor {
 public:
  // targetSeconds ≤ 0: no target, always full resolution.
  ResolutionGovernor(double targetSeconds, int maxScale);

  // A finished frame: the samples it rendered (pixels × samples per pixel) and the seconds the
  // renderer spent on it.
  void frameFinished(uint64_t samples, double seconds);

  // The scale for a frame of width × height at 1 sample per pixel: 1 is full resolution. Before
  // any frame has been measured, maxScale (the cheapest frame: something on screen soon).
  int scaleFor(int width, int height) const;

  // Samples per second over the recent frames (median); 0 before the first.
  double samplesPerSecond() const;

  double targetSeconds() const { return target_; }
  int maxScale() const { return maxScale_; }

 private:
  static constexpr size_t kWindow = 5;  // recent frames whose rates are kept

  double target_;
  int maxScale_;
  std::deque<double> rates_;  // samples per second, newest last
};

}  // namespace prism

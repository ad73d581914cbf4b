// Chooses the resolution of the viewer's frames while the camera moves: full resolution when a
// frame is predicted to fit the frame-time target, else the finest step of the ladder
// (master/live/FrameScale.h) that fits, down to 1/maxScale of each side. So the resolution drops
// only when a frame would miss the target, and comes back as soon as one fits.
//
// The prediction: the median time of the recent frames of that very size when there are some;
// otherwise the recent frames' time rescaled to the new size, a frame's fixed cost (tile
// hand-out, messages, the frame's end) kept apart from the cost per sample. Counting it per
// sample would over-predict larger frames: a frame at 1/2 that takes 19 ms with 4 ms of it fixed
// predicts 34 ms at 2/3, where 31 ms is what it takes. The fixed cost is estimated whenever the
// recent frames have two sizes (a still camera's full-resolution passes, then a move's first
// reduced frames): the line through the median times of the smallest and largest.
// Pure bookkeeping (times are passed in), tested without threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "master/live/FrameScale.h"

namespace prism {

class ResolutionGovernor {
 public:
  // targetSeconds ≤ 0: no target, always full resolution.
  ResolutionGovernor(double targetSeconds, int maxScale);

  // A finished frame: the samples it rendered (pixels × samples per pixel) and the seconds the
  // renderer spent on it.
  void frameFinished(uint64_t samples, double seconds);

  // The scale for a frame of width × height at 1 sample per pixel. Before any frame has been
  // measured, the coarsest step (the cheapest frame: something on screen soon).
  FrameScale scaleFor(int width, int height) const;

  // Seconds a frame of `samples` samples is predicted to take; 0 before the first frame.
  double predictSeconds(uint64_t samples) const;
  // The fixed cost of a frame, as last estimated (0 until the frames have had two sizes).
  double fixedSeconds() const { return fixed_; }

  double targetSeconds() const { return target_; }
  // A new target (a viewer asked for another frame time); the frames measured still count.
  void setTargetSeconds(double seconds) { target_ = seconds; }

 private:
  static constexpr size_t kWindow = 8;  // recent frames kept

  struct Frame {
    uint64_t samples;
    double seconds;
  };
  // Median seconds of the recent frames with this many samples; 0 if none.
  double medianSecondsOf(uint64_t samples) const;

  double target_;
  std::vector<FrameScale> ladder_;
  std::deque<Frame> frames_;  // newest last
  double fixed_ = 0.0;
};

}  // namespace prism

// Where display news waits for its viewer, merged: the frame's display bytes, the rectangle that
// changed since the viewer last took, the passes completed meanwhile (the newest
// DisplayNews::kMaxCompleted), the newest pass state, tiles in flight and statistics. Memory is
// one frame of display bytes however slowly the viewer takes, and take() gives the newest
// picture. The rendering side (LiveFeed) and the receiving side of a connection
// (master/remote/ViewClient.h) each keep one. Not thread-safe: its owner locks.
#pragma once

#include <cstdint>
#include <vector>

#include "master/live/DisplayNews.h"

namespace prism {

// Writes news's patch into frame (width × height display pixels). Throws std::invalid_argument
// for news of another frame size, or a patch outside the frame or of the wrong size.
void writePatch(std::vector<uint8_t>& frame, int width, int height, const DisplayNews& news);

class NewsBoard {
 public:
  NewsBoard(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  // The display bytes of the whole frame, as the viewer will see them once it takes.
  const std::vector<uint8_t>& bytes() const { return bytes_; }
  std::vector<uint8_t>& bytes() { return bytes_; }

  // The pixels of rect (already written into bytes()) changed.
  void markChanged(const TileRect& rect);
  // News from elsewhere: its patch goes into bytes(), its state replaces this one's, its
  // completed passes are added. Throws std::invalid_argument for a patch outside the frame or
  // of the wrong size, or news of another frame size.
  void post(DisplayNews&& news);
  // The state on show now (pass, tiles, counts); stats replace the last ones.
  void setState(const DisplayNews& state);
  void passCompleted(const DisplayPass& pass);
  void setStats(const LiveStats& stats);

  // Whether anything arrived since the last take().
  bool hasNews() const { return fresh_; }
  // Everything since the last take(), merged; `whole`: with every pixel (a viewer that has
  // nothing yet).
  DisplayNews take(bool whole = false);

 private:
  int width_;
  int height_;
  std::vector<uint8_t> bytes_;
  DisplayNews state_;  // pass state, in flight, counts (no patch, no completed)
  std::vector<DisplayPass> completed_;
  std::optional<LiveStats> stats_;
  int x0_, y0_, x1_ = 0, y1_ = 0;  // the changed rectangle (empty when x1_ ≤ x0_)
  bool fresh_ = false;
};

}  // namespace prism

// The frame a window shows: display bytes and the state of the pass on screen, as the news it
// took left them (DisplayNews). Plain C++; the window paints its bytes.
#pragma once

#include <cstdint>
#include <vector>

#include "master/live/DisplayNews.h"

namespace prism {

class DisplayFrame {
 public:
  DisplayFrame(int width, int height)
      : width_(width), height_(height), bytes_(static_cast<size_t>(width) * height * 3, 0) {
    state_.width = width;
    state_.height = height;
  }

  // Takes the news in (writePatch's checks); the state becomes the news's.
  void apply(const DisplayNews& news);

  int width() const { return width_; }
  int height() const { return height_; }
  // R, G, B per pixel, rows from the top.
  const std::vector<uint8_t>& bytes() const { return bytes_; }
  // The news's state: pass, tiles done, tiles in flight, counts (no patch).
  const DisplayNews& state() const { return state_; }
  const DisplayPass& pass() const { return state_.pass; }
  uint32_t frame() const { return state_.pass.frame; }
  bool passComplete() const {
    return state_.pass.tiles > 0 && state_.tilesDone == state_.pass.tiles;
  }

 private:
  int width_;
  int height_;
  std::vector<uint8_t> bytes_;
  DisplayNews state_;
};

}  // namespace prism

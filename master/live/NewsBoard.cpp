#include "master/live/NewsBoard.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace prism {

NewsBoard::NewsBoard(int width, int height)
    : width_(width),
      height_(height),
      bytes_(static_cast<size_t>(width) * height * 3, 0),
      x0_(width),
      y0_(height) {
  state_.width = width;
  state_.height = height;
}

void NewsBoard::markChanged(const TileRect& r) {
  if (r.width <= 0 || r.height <= 0) return;
  x0_ = std::min(x0_, r.x);
  y0_ = std::min(y0_, r.y);
  x1_ = std::max(x1_, r.x + r.width);
  y1_ = std::max(y1_, r.y + r.height);
  fresh_ = true;
}

void NewsBoard::setState(const DisplayNews& state) {
  state_.copyStateFrom(state);
  fresh_ = true;
}

void NewsBoard::passCompleted(const DisplayPass& pass) {
  if (completed_.size() == DisplayNews::kMaxCompleted) completed_.erase(completed_.begin());
  completed_.push_back(pass);
  fresh_ = true;
}

void NewsBoard::setStats(const LiveStats& stats) {
  stats_ = stats;
  fresh_ = true;
}

void writePatch(std::vector<uint8_t>& frame, int width, int height, const DisplayNews& news) {
  if (news.width != width || news.height != height) {
    throw std::invalid_argument("news of a " + std::to_string(news.width) + "x" +
                                std::to_string(news.height) + " frame for a " +
                                std::to_string(width) + "x" + std::to_string(height) + " one");
  }
  if (!news.hasPixels()) return;
  const TileRect& r = news.patch;
  if (r.x < 0 || r.y < 0 || r.x + r.width > width || r.y + r.height > height ||
      news.patchBytes.size() != static_cast<size_t>(r.width) * r.height * 3) {
    throw std::invalid_argument("a patch outside the frame or of the wrong size");
  }
  const size_t row = static_cast<size_t>(r.width) * 3;
  for (int y = 0; y < r.height; ++y) {
    std::memcpy(&frame[(static_cast<size_t>(r.y + y) * width + r.x) * 3], &news.patchBytes[y * row],
                row);
  }
}

void NewsBoard::post(DisplayNews&& news) {
  writePatch(bytes_, width_, height_, news);
  if (news.hasPixels()) markChanged(news.patch);
  setState(news);
  for (DisplayPass& p : news.completed) passCompleted(p);
  if (news.stats) setStats(*news.stats);
}

DisplayNews NewsBoard::take(bool whole) {
  DisplayNews news = state_;
  news.completed = std::move(completed_);
  completed_.clear();
  news.stats = std::move(stats_);
  stats_.reset();
  if (whole) {
    x0_ = y0_ = 0;
    x1_ = width_;
    y1_ = height_;
  }
  if (x1_ > x0_ && y1_ > y0_) {
    news.patch = {x0_, y0_, x1_ - x0_, y1_ - y0_};
    const size_t row = static_cast<size_t>(news.patch.width) * 3;
    news.patchBytes.resize(row * news.patch.height);
    for (int y = 0; y < news.patch.height; ++y) {
      std::memcpy(&news.patchBytes[y * row],
                  &bytes_[(static_cast<size_t>(y0_ + y) * width_ + x0_) * 3], row);
    }
  }
  x0_ = width_;
  y0_ = height_;
  x1_ = y1_ = 0;
  fresh_ = false;
  return news;
}

}  // namespace prism

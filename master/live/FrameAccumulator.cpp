#include "master/live/FrameAccumulator.h"

#include <algorithm>

namespace prism {
namespace {
constexpr int kNone = -1;
constexpr int kDone = -2;
}  // namespace

FrameAccumulator::FrameAccumulator(int width, int height)
    : image_(width, height), dirtyX0_(width), dirtyY0_(height) {}

void FrameAccumulator::beginPass(const PassInfo& pass) {
  if (!started_ || pass.viewId != pass_.viewId) completedPass_ = -1;
  pass_ = pass;
  started_ = true;
  owner_.assign(pass.tiles.size(), kNone);
  tilesDone_ = 0;
}

bool FrameAccumulator::assign(uint32_t frame, uint32_t tile, int rank) {
  if (!started_ || frame != pass_.frame || tile >= owner_.size()) return false;
  if (owner_[tile] != kDone) owner_[tile] = rank;
  return true;
}

TileRect FrameAccumulator::toDisplay(const TileRect& r) const {
  const int w = pass_.view ? pass_.view->width : image_.width;
  const int h = pass_.view ? pass_.view->height : image_.height;
  const int x0 = static_cast<int>(int64_t{r.x} * image_.width / w);
  const int y0 = static_cast<int>(int64_t{r.y} * image_.height / h);
  const int x1 = static_cast<int>(int64_t{r.x + r.width} * image_.width / w);
  const int y1 = static_cast<int>(int64_t{r.y + r.height} * image_.height / h);
  return {x0, y0, x1 - x0, y1 - y0};
}

void FrameAccumulator::write(ImageRgb& target, const TileResult& tile) const {
  const TileRect& r = tile.rect;
  const int w = pass_.view->width;
  const int h = pass_.view->height;
  if (!pass_.scale.full() || w != target.width || h != target.height) {
    // A reduced frame: each of its pixels covers a block of display pixels.
    for (int ty = 0; ty < r.height; ++ty) {
      const int py = r.y + ty;
      const int y0 = static_cast<int>(int64_t{py} * target.height / h);
      const int y1 = static_cast<int>(int64_t{py + 1} * target.height / h);
      for (int tx = 0; tx < r.width; ++tx) {
        const int px = r.x + tx;
        const int x0 = static_cast<int>(int64_t{px} * target.width / w);
        const int x1 = static_cast<int>(int64_t{px + 1} * target.width / w);
        const Color& c = tile.pixels[static_cast<size_t>(ty) * r.width + tx];
        for (int y = y0; y < y1; ++y) {
          std::fill(&target.at(x0, y), &target.at(x0, y) + (x1 - x0), c);
        }
      }
    }
    return;
  }
  // Full-resolution pass p averages with the p - 1 before it; pass 1 replaces what was there
  // (copied, so it is exactly the image `prism render` makes).
  const bool first = pass_.pass <= 1;
  const float weight = 1.0f / static_cast<float>(std::max(pass_.pass, 1));
  for (int ty = 0; ty < r.height; ++ty) {
    for (int tx = 0; tx < r.width; ++tx) {
      Color& mean = target.at(r.x + tx, r.y + ty);
      const Color& sample = tile.pixels[static_cast<size_t>(ty) * r.width + tx];
      mean = first ? sample : mean + (sample - mean) * weight;
    }
  }
}

bool FrameAccumulator::addTile(uint32_t frame, const TileResult& tile) {
  if (!started_ || frame != pass_.frame || tile.tileIndex >= owner_.size() ||
      owner_[tile.tileIndex] == kDone) {
    ++staleTiles_;
    return false;
  }
  // A view's first frame is only a pass 0 or 1, which replace every pixel: the back buffer
  // needs no earlier content.
  const bool whole = pass_.firstOfView;
  if (whole && (back_.width != image_.width || back_.height != image_.height)) {
    back_ = ImageRgb(image_.width, image_.height);
  }
  write(whole ? back_ : image_, tile);
  owner_[tile.tileIndex] = kDone;
  if (++tilesDone_ == owner_.size()) {
    completedPass_ = pass_.pass;
    if (whole) {
      std::swap(image_, back_);
      markDirty({0, 0, image_.width, image_.height});
    }
  }
  if (!whole) markDirty(toDisplay(tile.rect));
  return true;
}

std::vector<FrameAccumulator::InFlight> FrameAccumulator::inFlight() const {
  std::vector<InFlight> tiles;
  for (size_t i = 0; i < owner_.size(); ++i) {
    if (owner_[i] >= 0) tiles.push_back({toDisplay(pass_.tiles[i]), owner_[i]});
  }
  return tiles;
}

void FrameAccumulator::markDirty(const TileRect& r) {
  dirtyX0_ = std::min(dirtyX0_, r.x);
  dirtyY0_ = std::min(dirtyY0_, r.y);
  dirtyX1_ = std::max(dirtyX1_, r.x + r.width);
  dirtyY1_ = std::max(dirtyY1_, r.y + r.height);
}

TileRect FrameAccumulator::takeDirty() {
  TileRect r{0, 0, 0, 0};
  if (dirtyX1_ > dirtyX0_ && dirtyY1_ > dirtyY0_) {
    r = {dirtyX0_, dirtyY0_, dirtyX1_ - dirtyX0_, dirtyY1_ - dirtyY0_};
  }
  dirtyX0_ = image_.width;
  dirtyY0_ = image_.height;
  dirtyX1_ = dirtyY1_ = 0;
  return r;
}

}  // namespace prism

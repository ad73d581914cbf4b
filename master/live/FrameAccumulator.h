// The image the viewer shows, assembled from the tiles of successive passes: a reduced frame
// fills blocks of display pixels, full-resolution passes are averaged (pass p contributes 1/p),
// so a still camera converges to more samples per pixel. The first frame of a view is
// assembled aside and shown whole once complete, so the screen never mixes two views; later
// passes show their tiles as they arrive. Knows which tiles are in flight and on which rank, and
// ignores tiles of frames it is no longer showing. Plain C++, no Qt.
#pragma once

#include <cstdint>
#include <vector>

#include "image/ImageRgb.h"
#include "master/live/LiveRenderer.h"

namespace prism {

class FrameAccumulator {
 public:
  FrameAccumulator(int width, int height);

  void beginPass(const PassInfo& pass);
  // Both return false (and change nothing) for a frame other than the current one.
  bool assign(uint32_t frame, uint32_t tile, int rank);
  bool addTile(uint32_t frame, const TileResult& tile);

  struct InFlight {
    TileRect rect;  // in display pixels
    int rank = 0;
  };
  std::vector<InFlight> inFlight() const;

  // The display-pixel rectangle changed since the last call (width 0: nothing).
  TileRect takeDirty();

  const ImageRgb& image() const { return image_; }
  const PassInfo& pass() const { return pass_; }
  uint32_t frame() const { return pass_.frame; }
  size_t tilesDone() const { return tilesDone_; }
  bool passComplete() const { return !pass_.tiles.empty() && tilesDone_ == pass_.tiles.size(); }
  size_t staleTiles() const { return staleTiles_; }
  // The highest pass of the current view whose every tile is in (-1: none yet). The next pass
  // may already be under way, so passComplete() alone misses it.
  int completedPass() const { return completedPass_; }

  // A rectangle of the pass's image in display pixels.
  TileRect toDisplay(const TileRect& r) const;

 private:
  void markDirty(const TileRect& r);
  void write(ImageRgb& target, const TileResult& tile) const;

  ImageRgb image_;
  ImageRgb back_;  // the first frame of a view, until it is complete
  PassInfo pass_;
  bool started_ = false;
  int completedPass_ = -1;
  std::vector<int> owner_;  // per tile: rendering rank, kNone or kDone
  size_t tilesDone_ = 0;
  size_t staleTiles_ = 0;
  int dirtyX0_, dirtyY0_, dirtyX1_ = 0, dirtyY1_ = 0;
};

}  // namespace prism

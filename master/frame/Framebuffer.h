// Assembles tile results into the frame. A tile that arrives twice (a re-issued job whose first
// worker answered late) is ignored, so the frame never mixes two copies.
#pragma once

#include <utility>
#include <vector>

#include "image/ImageRgb.h"
#include "render/Tile.h"

namespace prism {

class Framebuffer {
 public:
  Framebuffer(int width, int height, size_t tileCount);

  // Copies the tile's pixels into the frame; returns false (and copies nothing) for a
  // duplicate or a tile that does not fit the frame.
  bool insert(const TileResult& tile);

  size_t tilesDone() const { return tilesDone_; }
  size_t tileCount() const { return received_.size(); }
  bool complete() const { return tilesDone_ == received_.size(); }
  const ImageRgb& image() const { return image_; }
  // The finished frame, moved out: the framebuffer holds no image afterwards.
  ImageRgb takeImage() { return std::move(image_); }
  const std::vector<bool>& received() const { return received_; }  // index = tile

 private:
  ImageRgb image_;
  std::vector<bool> received_;
  size_t tilesDone_ = 0;
};

}  // namespace prism

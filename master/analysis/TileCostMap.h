// Where a frame's render time goes, measured once and reused at other image and tile sizes:
// the per-tile times of a measured frame spread evenly over each tile's pixels give a cost
// density over the image; a tile of another plan costs the density integrated over the same
// part of the image, scaled by the ratio of pixel counts (the same samples per pixel cost the
// same per pixel at any resolution). This is what the scheduling simulator replays.
#pragma once

#include <vector>

#include "render/Tile.h"

namespace prism {

class TileCostMap {
 public:
  // tiles must be a plan of planTiles(width, height, edge) for one edge; seconds[i] is tile i's.
  // Throws std::invalid_argument when the sizes differ or the plan is not such a grid.
  TileCostMap(int width, int height, const std::vector<TileRect>& tiles,
              const std::vector<double>& seconds);

  // The cost of every tile of planTiles(width, height, tileSize), in plan order.
  std::vector<double> tileCosts(int width, int height, int tileSize) const;

  double totalSeconds() const { return total_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  int edge_;                     // the measured plan's tile edge
  int columns_, rows_;           // of the measured plan
  std::vector<double> density_;  // seconds per pixel, one value per measured tile
  double total_ = 0.0;
};

}  // namespace prism

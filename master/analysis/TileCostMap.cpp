#include "master/analysis/TileCostMap.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "master/frame/TilePlan.h"

namespace prism {

TileCostMap::TileCostMap(int width, int height, const std::vector<TileRect>& tiles,
                         const std::vector<double>& seconds)
    : width_(width), height_(height), edge_(tiles.empty() ? 0 : tiles.front().width) {
  if (tiles.empty() || tiles.size() != seconds.size() || edge_ <= 0) {
    throw std::invalid_argument("TileCostMap: one time per tile of a non-empty plan needed");
  }
  columns_ = (width + edge_ - 1) / edge_;
  rows_ = (height + edge_ - 1) / edge_;
  const std::vector<TileRect> plan = planTiles(width, height, edge_);
  if (plan.size() != tiles.size()) {
    throw std::invalid_argument("TileCostMap: the tiles are not a plan of the image");
  }
  density_.resize(tiles.size());
  for (size_t i = 0; i < tiles.size(); ++i) {
    const TileRect& a = tiles[i];
    const TileRect& b = plan[i];
    if (a.x != b.x || a.y != b.y || a.width != b.width || a.height != b.height) {
      throw std::invalid_argument("TileCostMap: the tiles are not a plan of the image");
    }
    density_[i] = seconds[i] / a.pixelCount();
    total_ += seconds[i];
  }
}

std::vector<double> TileCostMap::tileCosts(int width, int height, int tileSize) const {
  // Target pixel coordinates scaled into measured ones.
  const double sx = static_cast<double>(width_) / width;
  const double sy = static_cast<double>(height_) / height;
  const double pixelRatio = 1.0 / (sx * sy);  // target pixels per measured pixel
  std::vector<double> costs;
  for (const TileRect& t : planTiles(width, height, tileSize)) {
    const double x0 = t.x * sx, x1 = (t.x + t.width) * sx;
    const double y0 = t.y * sy, y1 = (t.y + t.height) * sy;
    const int c0 = static_cast<int>(x0 / edge_);
    const int c1 = std::min(columns_ - 1, static_cast<int>(std::ceil(x1 / edge_)) - 1);
    const int r0 = static_cast<int>(y0 / edge_);
    const int r1 = std::min(rows_ - 1, static_cast<int>(std::ceil(y1 / edge_)) - 1);
    double seconds = 0.0;  // measured seconds over the same part of the image
    for (int r = r0; r <= r1; ++r) {
      const double overlapY = std::min(y1, std::min<double>((r + 1) * edge_, height_)) -
                              std::max<double>(y0, r * edge_);
      for (int c = c0; c <= c1; ++c) {
        const double overlapX = std::min(x1, std::min<double>((c + 1) * edge_, width_)) -
                                std::max<double>(x0, c * edge_);
        if (overlapX > 0.0 && overlapY > 0.0) {
          seconds += overlapX * overlapY * density_[static_cast<size_t>(r) * columns_ + c];
        }
      }
    }
    costs.push_back(seconds * pixelRatio);
  }
  return costs;
}

}  // namespace prism

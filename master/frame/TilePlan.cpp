#include "master/frame/TilePlan.h"

#include <algorithm>
#include <cmath>

namespace prism {

std::vector<TileRect> planTiles(int imageWidth, int imageHeight, int tileSize) {
  std::vector<TileRect> tiles;
  for (int y = 0; y < imageHeight; y += tileSize) {
    for (int x = 0; x < imageWidth; x += tileSize) {
      tiles.push_back(
          {x, y, std::min(tileSize, imageWidth - x), std::min(tileSize, imageHeight - y)});
    }
  }
  return tiles;
}

int automaticTileSize(int imageWidth, int imageHeight, int workerThreads) {
  constexpr double kTilesPerWorker = 16.0;
  const double pixelsPerTile = static_cast<double>(imageWidth) * imageHeight /
                               (kTilesPerWorker * std::max(1, workerThreads));
  const int edge = static_cast<int>(std::sqrt(pixelsPerTile) / 8.0) * 8;
  return std::clamp(edge, 8, 64);
}

int streamedTileSize(int imageWidth, int imageHeight, int samplesPerPixel, int workerThreads) {
  constexpr double kMinTileSamples = 16384.0;
  constexpr double kMinTilesPerWorker = 4.0;
  const double bySamples = std::sqrt(kMinTileSamples / std::max(1, samplesPerPixel));
  const double byBalance = std::sqrt(static_cast<double>(imageWidth) * imageHeight /
                                     (kMinTilesPerWorker * std::max(1, workerThreads)));
  const int edge = static_cast<int>(std::min(bySamples, byBalance) / 8.0) * 8;
  return std::clamp(edge, 8, 128);
}

}  // namespace prism

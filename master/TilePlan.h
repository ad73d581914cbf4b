// Splits an image into square tiles (the edge tiles may be smaller), in row-major order.
#pragma once

#include <vector>

#include "render/Tile.h"

namespace prism {

std::vector<TileRect> planTiles(int imageWidth, int imageHeight, int tileSize);

// A tile edge giving every worker thread about 16 tiles, so a few slow tiles cannot leave the
// others idle at the end of the frame, while keeping tiles between 8 and 64 pixels (per-tile
// overheads stay negligible). Always a multiple of 8.
int automaticTileSize(int imageWidth, int imageHeight, int workerThreads);

}  // namespace prism

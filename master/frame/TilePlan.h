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

// The viewer's tile edge. Its frames follow one another pipelined, so a frame's end needs less
// balancing (about 4 tiles per worker thread suffice), while a 1-spp tile is cheap beside what
// handing it out and back costs (with slaves about 0.2 ms of the coordinator's and the slave's
// time a tile, a sixth of a 64² tile's rendering): tiles hold at least 16 k samples where the
// balance allows, and stay between 8 and 128 pixels. Always a multiple of 8.
int streamedTileSize(int imageWidth, int imageHeight, int samplesPerPixel, int workerThreads);

}  // namespace prism

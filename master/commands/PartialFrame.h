// The frame an interrupted `prism render --save-partial` leaves: the finished tiles, the others
// striped magenta and black so no one takes them for dark scenery, under a name that says
// "partial" (frame.png -> frame.partial.png) and with the tile count in the file's metadata
// (PNG text chunk / EXR attribute "PrismPartial" = "done/total"), so neither a person nor a
// script mistakes it for the finished frame.
#pragma once

#include <string>
#include <vector>

#include "image/ImageIo.h"
#include "image/ImageRgb.h"
#include "render/Tile.h"

namespace prism {

inline constexpr const char* kPartialFrameAttribute = "PrismPartial";

// "out/frame.png" -> "out/frame.partial.png".
std::string partialOutputPath(const std::string& outputPath);

// Stripes every tile that tileDone (index = tile) does not mark.
void markUnfinishedTiles(ImageRgb& image, const std::vector<TileRect>& tiles,
                         const std::vector<bool>& tileDone);

// "PrismPartial" = "57/120" and an ImageDescription that says it in words.
ImageMetadata partialFrameMetadata(size_t tilesDone, size_t tileCount);

// Whether the image file at path was written as a partial frame.
bool isPartialFrame(const std::string& path);

// Refuses (std::runtime_error) to replace a finished frame at path unless overwrite is set; a
// partial frame from an earlier run may always be replaced.
void checkMayWriteFrame(const std::string& path, bool overwrite);

}  // namespace prism

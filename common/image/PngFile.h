// PNG through libpng: the 8-bit display image of every `-o x.png` render, and the PNGs users
// bring (cube-map faces). Only the common case is read here (8-bit RGB or grey without
// transparency); other PNGs (palette, 16-bit, alpha) are left to OpenImageIO (ImageIo.cpp) so
// that they read exactly as they always have.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "image/ImageIo.h"
#include "image/SrgbImage.h"

namespace prism {

// Writes width×height RGB bytes (row-major from the top left, already sRGB-encoded) to path,
// tagged sRGB, with metadata as tEXt chunks ("ImageDescription" is stored under PNG's keyword
// "Description"). Throws std::runtime_error with libpng's message (without the path).
// The zlib level and the row filters trade file size for time. The defaults, measured on a 512²
// render (docs/journal/2026-11-23-png-and-exr-encoding.md): zlib level 1 with the Sub filter on
// every row encodes in 8 ms to 189 KiB, where OpenImageIO's settings (level 3, libpng's adaptive
// choice among all five filters) took 17 ms for 181 KiB.
struct PngEncoding {
  int zlibLevel = 1;
  int filters = 0x10;  // PNG_FILTER_SUB
};
void writePng(const std::string& path, int width, int height, const uint8_t* rgb,
              const ImageMetadata& metadata, const PngEncoding& encoding = {});

// The decoded bytes of an 8-bit RGB or grey PNG, expanded to RGB; nullopt when the file is a PNG
// of another kind (OpenImageIO reads those). Throws std::runtime_error for a missing, unreadable
// or corrupt file.
std::optional<SrgbImage> readPng(const std::string& path);

// A PNG's pixels decoded from its bytes in memory, whatever its kind: 8-bit files (grey,
// palette, RGB, with or without alpha) as sRGB bytes, expanded to RGB (alpha dropped), 16-bit
// files as linear radiance (the sRGB curve applied to value/65535). Exactly one of the two
// holds pixels. maxPixels: a file of more pixels is refused from its header, before any is
// decoded. Throws std::runtime_error with libpng's message (or the size refused).
struct PngPixels {
  SrgbImage srgb;
  ImageRgb linear;
  bool hadAlpha = false;
};
PngPixels decodePng(std::span<const uint8_t> bytes, uint64_t maxPixels);

// The text chunk (tEXt, zTXt or iTXt before the image data) named name ("ImageDescription" looks
// for "Description"); nullopt when there is none or the file is not a readable PNG.
std::optional<std::string> readPngText(const std::string& path, const std::string& name);

}  // namespace prism

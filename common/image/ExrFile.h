// OpenEXR through its C library (OpenEXRCore: one shared library plus zlib, no C++ runtime of its
// own to load): the linear float image of every `-o x.exr` render, untouched, and the EXRs users
// bring. Only single-part scanline files with R, G and B channels (half, float or uint) are read
// here; other EXRs (tiled, multi-part, deep, luminance, subsampled) are left to OpenImageIO
// (ImageIo.cpp).
#pragma once

#include <optional>
#include <string>

#include "image/ImageIo.h"

namespace prism {

// Compression and zlib level trade file size for time; the defaults are measured in
// docs/performance.md ("Fixed costs"). compression is OpenEXR's exr_compression_t value.
struct ExrEncoding {
  int compression = 2;  // EXR_COMPRESSION_ZIPS: zlib on single scanlines
  int zipLevel = 1;
};

// Writes image as 32-bit float R, G, B to path, with metadata as string attributes
// ("ImageDescription" is stored as OpenEXR's "comments"). Throws std::runtime_error with
// OpenEXR's message (without the path).
void writeExr(const std::string& path, const ImageRgb& image, const ImageMetadata& metadata,
              const ExrEncoding& encoding = {});

// The pixels of a single-part scanline EXR with R, G and B channels; nullopt for an EXR of
// another kind. Throws std::runtime_error for a missing, unreadable or corrupt file.
std::optional<ImageRgb> readExr(const std::string& path);

// A string attribute of the first part ("ImageDescription" looks for "comments"); nullopt when
// absent, not a string, or the file is not a readable EXR.
std::optional<std::string> readExrText(const std::string& path, const std::string& name);

}  // namespace prism

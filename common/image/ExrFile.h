// OpenEXR through its C library (OpenEXRCore: one shared library plus zlib, no C++ runtime of its
// own to load): the linear float image of every `-o x.exr` render, untouched, and the EXRs users
// bring. Only single-part scanline files with R, G and B channels of half or float are read here;
// other EXRs (tiled, multi-part, deep, luminance, subsampled, integer) are left to OpenImageIO
// (ImageIo.cpp).
#pragma once

#include <optional>
#include <string>

#include "image/ImageIo.h"

namespace prism {

// Compression trades file size for time; compression is OpenEXR's exr_compression_t value. The
// default is none: on a rendered 512² frame the lossless methods save 3 % (ZIPS), 11 % (ZIP) or
// 14 % (PIZ) of 3 MiB, because the low mantissa bits of float radiance are noise, for 8 to 17
// times the 7.5 ms an uncompressed write takes (docs/journal/2026-11-23-png-and-exr-encoding.md).
struct ExrEncoding {
  int compression = 0;  // EXR_COMPRESSION_NONE
  int zipLevel = 4;     // OpenEXR's default, for ZIP and ZIPS
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

// Image files. The format follows the extension: EXR (and other float formats) get linear radiance
// untouched; PNG/JPEG get exposure, clamping and the sRGB curve. PNG and EXR, the formats every
// render writes, go through libpng and OpenEXR (PngFile.h, ExrFile.h); every other format through
// OpenImageIO, loaded only when such a file is read or written (OiioModule.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "image/ImageRgb.h"
#include "image/SrgbImage.h"

namespace prism {

// Text stored with the pixels (PNG tEXt chunks, EXR string attributes): (name, value) pairs.
using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

// Writes image to path via a temporary file in the same folder that is renamed on success, so a
// failed or interrupted write never leaves a half-written file. Throws std::runtime_error.
void writeImage(const ImageRgb& image, const std::string& path, float exposure = 1.0f,
                const ImageMetadata& metadata = {});

// Writes display bytes (R, G, B per pixel, sRGB-encoded, rows from the top) as a PNG, the same
// way: what a viewer shows, saved as it shows it. Throws std::runtime_error.
void writeDisplayPng(const std::string& path, int width, int height,
                     const std::vector<uint8_t>& rgb);

// A text attribute of an image file written with metadata; "" when the file has none of that
// name or cannot be read.
std::string readImageText(const std::string& path, const std::string& name);

// Reads any format OpenImageIO knows into linear RGB (sRGB-encoded 8-bit files are linearised).
// Throws std::runtime_error naming the file.
ImageRgb readImage(const std::string& path);

// The file's bytes where it is an 8-bit sRGB image that libpng reads (RGB or grey PNG), for
// callers that keep them as bytes (cube-map faces); nullopt for any other file (readImage reads
// those). Throws std::runtime_error naming the file for a missing or corrupt PNG.
std::optional<SrgbImage> readSrgbImage(const std::string& path);

// readImage through OpenImageIO whatever the format (loads the module): what readImage gives for
// formats libpng and OpenEXR do not read here, and the yardstick the tests hold those readers to.
ImageRgb readImageWithOpenImageIo(const std::string& path);

// True when path's extension names a format this build can write.
bool isWritableImagePath(const std::string& path, std::string* why = nullptr);

}  // namespace prism

// Image files through OpenImageIO. The format follows the extension: EXR (and other float
// formats) get linear radiance untouched; PNG/JPEG get exposure, clamping and the sRGB curve.
#pragma once

#include <string>

#include "image/ImageRgb.h"

namespace prism {

// Writes image to path via a temporary file in the same folder that is renamed on success, so a
// failed or interrupted write never leaves a half-written file. Throws std::runtime_error.
void writeImage(const ImageRgb& image, const std::string& path, float exposure = 1.0f);

// Reads any format OpenImageIO knows into linear RGB (sRGB-encoded 8-bit files are linearised).
// Throws std::runtime_error naming the file.
ImageRgb readImage(const std::string& path);

// True when path's extension names a format this build can write.
bool isWritableImagePath(const std::string& path, std::string* why = nullptr);

}  // namespace prism

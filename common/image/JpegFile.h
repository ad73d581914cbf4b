// JPEG through libjpeg(-turbo): the textures models bring, kept as the 8-bit sRGB bytes they
// are. Only decoding: Prism writes no JPEG.
#pragma once

#include <cstdint>
#include <span>

#include "image/SrgbImage.h"

namespace prism {

// The pixels of a baseline or progressive JPEG in memory, grey and CMYK converted to RGB.
// maxPixels: a larger image is refused from its header, before any pixel is decoded. Throws
// std::runtime_error with libjpeg's message (or the size refused).
SrgbImage decodeJpeg(std::span<const uint8_t> bytes, uint64_t maxPixels);

}  // namespace prism

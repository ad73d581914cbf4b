// A frame that is only shown (the viewer's frames while the camera moves) needs no more than
// the window shows of it: 8-bit display bytes (ToneMap.h), 3 a pixel instead of 12. Tiles of
// such frames travel between ranks this way (wire::TileResultMessage) and arrive as radiance
// that shows as the same bytes.
#pragma once

#include <cstdint>
#include <vector>

#include "math/Vec.h"

namespace prism {

// Whether tiles can travel as display bytes at this exposure: each byte has a radiance that
// shows as it (DisplayEncoder::invertible; false for exposures so extreme that the sRGB
// thresholds overflow or underflow, and for exposures that are not positive and finite).
bool displayBytesInvertible(float exposure);
// R, G, B bytes of each pixel as the viewer shows it at this exposure (> 0).
std::vector<uint8_t> toDisplayBytes(const std::vector<Color>& pixels, float exposure);
// For each three bytes, the smallest radiance that shows as them at this exposure
// (DisplayEncoder::lowestRadianceOf): toDisplayBytes of the result gives the bytes back.
std::vector<Color> fromDisplayBytes(const std::vector<uint8_t>& bytes, float exposure);

}  // namespace prism

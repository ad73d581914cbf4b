#include "image/DisplayBytes.h"

#include <cmath>
#include <memory>

#include "image/ToneMap.h"

namespace prism {
namespace {

// Building an encoder takes about a millisecond (its bucket table); a rank sends tile after
// tile at one exposure, so each thread keeps the last one.
const DisplayEncoder& encoderFor(float exposure) {
  thread_local float cachedExposure = 0.0f;
  thread_local std::unique_ptr<DisplayEncoder> cached;
  if (!cached || cachedExposure != exposure) {
    cached = std::make_unique<DisplayEncoder>(exposure);
    cachedExposure = exposure;
  }
  return *cached;
}

}  // namespace

bool displayBytesInvertible(float exposure) {
  return exposure > 0.0f && std::isfinite(exposure) && encoderFor(exposure).invertible();
}

std::vector<uint8_t> toDisplayBytes(const std::vector<Color>& pixels, float exposure) {
  const DisplayEncoder& encode = encoderFor(exposure);
  std::vector<uint8_t> bytes(pixels.size() * 3);
  for (size_t i = 0; i < pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) bytes[3 * i + c] = encode(pixels[i][c]);
  }
  return bytes;
}

std::vector<Color> fromDisplayBytes(const std::vector<uint8_t>& bytes, float exposure) {
  const DisplayEncoder& encode = encoderFor(exposure);
  std::vector<Color> pixels(bytes.size() / 3);
  for (size_t i = 0; i < pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) pixels[i][c] = encode.lowestRadianceOf(bytes[3 * i + c]);
  }
  return pixels;
}

}  // namespace prism

// Display bytes for frames that are only shown: each byte comes back as a radiance that shows
// as that byte, at any exposure, and the bytes are the viewer's own encoding (ToneMap.h).
#include "image/DisplayBytes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "image/ToneMap.h"

namespace prism {
namespace {

TEST(DisplayBytes, EveryByteComesBackAsARadianceThatShowsAsIt) {
  for (const float exposure : {1.0f, 0.37f, 2.5f, 1000.0f}) {
    std::vector<uint8_t> bytes(3 * 256);
    for (int b = 0; b < 256; ++b) {
      bytes[3 * b] = static_cast<uint8_t>(b);
      bytes[3 * b + 1] = static_cast<uint8_t>(255 - b);
      bytes[3 * b + 2] = static_cast<uint8_t>((b * 7) % 256);
    }
    const std::vector<Color> radiance = fromDisplayBytes(bytes, exposure);
    ASSERT_EQ(radiance.size(), 256u);
    EXPECT_EQ(toDisplayBytes(radiance, exposure), bytes) << "exposure " << exposure;
  }
}

// An exposure so extreme that the sRGB thresholds overflow or underflow cannot carry bytes (the
// wire refuses it; the viewer then sends radiance): the wire fuzzer's find.
TEST(DisplayBytes, OnlyExposuresWhoseBytesComeBackCarryThem) {
  for (const float exposure : {1.0f, 1e-20f, 1e20f}) {
    EXPECT_TRUE(displayBytesInvertible(exposure)) << exposure;
  }
  for (const float exposure :
       {0.0f, -1.0f, 1e-39f, 1e-40f, 1e38f, std::numeric_limits<float>::infinity(),
        std::numeric_limits<float>::quiet_NaN()}) {
    EXPECT_FALSE(displayBytesInvertible(exposure)) << exposure;
  }
}

TEST(DisplayBytes, AreTheBytesTheViewerShows) {
  std::vector<Color> pixels;
  for (int i = 0; i < 2000; ++i) {
    const float v = std::pow(1.01f, static_cast<float>(i)) * 1e-5f;  // 1e-5 to 4e3
    pixels.push_back(Color(v, 1.0f / (1.0f + v), v * v));
  }
  pixels.push_back(Color(std::numeric_limits<float>::quiet_NaN(), -2.0f, 0.0f));
  const float exposure = 0.8f;
  const std::vector<uint8_t> bytes = toDisplayBytes(pixels, exposure);
  for (size_t i = 0; i < pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(bytes[3 * i + c], toDisplayByte(pixels[i][c], exposure)) << i << " " << c;
    }
  }
  // Shown again after the trip, the bytes are the same.
  EXPECT_EQ(toDisplayBytes(fromDisplayBytes(bytes, exposure), exposure), bytes);
}

}  // namespace
}  // namespace prism

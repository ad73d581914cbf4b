#include "image/SrgbImage.h"

#include <gtest/gtest.h>

#include "image/ToneMap.h"
#include "math/Random.h"

namespace prism {
namespace {

TEST(SrgbImage, EveryByteLinearisesThroughTheSrgbCurve) {
  const std::array<float, 256>& linear = linearOfSrgbByte();
  for (int b = 0; b < 256; ++b) {
    EXPECT_EQ(linear[b], srgbToLinear(static_cast<float>(b) * (1.0f / 255.0f))) << b;
  }
  EXPECT_EQ(linear[0], 0.0f);
  EXPECT_FLOAT_EQ(linear[255], 1.0f);
}

TEST(SrgbImage, PackingKeepsTheBytesAndEncodingRoundTripsEachByte) {
  SrgbImage image{3, 2, {}};
  for (int i = 0; i < 18; ++i) image.rgb.push_back(static_cast<uint8_t>(i * 14 + 3));
  const SrgbTexels packed = packedTexels(image);
  ASSERT_EQ(packed.width, 3);
  ASSERT_EQ(packed.height, 2);
  ASSERT_EQ(packed.texels.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ((packed.texels[i] >> (8 * c)) & 0xff, image.rgb[3 * i + c]) << i << "," << c;
    }
    EXPECT_EQ(packed.texels[i] >> 24, 0u);
  }
  // Radiance of a byte encodes back to that byte, and the decoded texels are linearFromSrgb's.
  const ImageRgb linear = linearFromSrgb(image);
  const SrgbTexels again = packedTexels(linear);
  EXPECT_EQ(again.texels, packed.texels);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) EXPECT_EQ(packed.at(x, y), linear.at(x, y)) << x << "," << y;
  }
}

TEST(SrgbImage, EncodingRoundsToTheNearestByteAndClamps) {
  // Halfway between two bytes in the encoded domain, just below and just above.
  const float below = srgbToLinear(100.49f / 255.0f), above = srgbToLinear(100.51f / 255.0f);
  ImageRgb image(4, 1);
  image.pixels = {Color(below, above, 0.0f), Color(-1.0f, 2.0f, 1.0f),
                  Color(std::nanf(""), 0.5f, 1e-9f), Color(0.0f)};
  const SrgbTexels packed = packedTexels(image);
  EXPECT_EQ(packed.texels[0] & 0xff, 100u);
  EXPECT_EQ((packed.texels[0] >> 8) & 0xff, 101u);
  EXPECT_EQ(packed.texels[1], 0u | 255u << 8 | 255u << 16);  // clamped to [0, 1]
  EXPECT_EQ(packed.texels[2] & 0xff, 0u);                    // NaN is black
  EXPECT_EQ((packed.texels[2] >> 8) & 0xff, 188u);           // 0.5 linear is byte 188
}

}  // namespace
}  // namespace prism

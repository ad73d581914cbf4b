#include "image/MipPyramid.h"

#include <gtest/gtest.h>

#include "math/Random.h"

namespace prism {
namespace {

ImageRgb randomImage(int width, int height, uint64_t seed) {
  ImageRgb image(width, height);
  Pcg32 rng(seed, 3);
  for (Color& c : image.pixels) c = Color(rng.nextFloat(), 10.0f * rng.nextFloat(), 0.5f);
  return image;
}

// The mean of an image's texels, in double.
glm::dvec3 mean(const ImageRgb& image) {
  glm::dvec3 sum(0.0);
  for (const Color& c : image.pixels) sum += glm::dvec3(c);
  return sum / static_cast<double>(image.pixels.size());
}

TEST(MipPyramid, HalvingAveragesEachTwoByTwoBlock) {
  // A checkerboard of single texels halves to its mean everywhere, exactly.
  ImageRgb checker(8, 8);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) checker.at(x, y) = Color(static_cast<float>((x + y) % 2));
  }
  const ImageRgb half = halved(checker);
  ASSERT_EQ(half.width, 4);
  ASSERT_EQ(half.height, 4);
  for (const Color& c : half.pixels) EXPECT_EQ(c, Color(0.5f));

  const ImageRgb image = randomImage(6, 4, 1);
  const ImageRgb level = halved(image);
  ASSERT_EQ(level.width, 3);
  ASSERT_EQ(level.height, 2);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) {
      const Color block = 0.25f * (image.at(2 * x, 2 * y) + image.at(2 * x + 1, 2 * y) +
                                   image.at(2 * x, 2 * y + 1) + image.at(2 * x + 1, 2 * y + 1));
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(level.at(x, y)[c], block[c], 1e-5f) << x << "," << y;
    }
  }
}

TEST(MipPyramid, AnOddSideHalvesToBoxesThatCutTexels) {
  // Three texels in a row halve to one covering all three; five to two, each covering 2.5:
  // the middle texel counts half in each.
  ImageRgb row(5, 1);
  for (int x = 0; x < 5; ++x) row.at(x, 0) = Color(static_cast<float>(1 << x));  // 1 2 4 8 16
  const ImageRgb two = halved(row);
  ASSERT_EQ(two.width, 2);
  EXPECT_FLOAT_EQ(two.at(0, 0).x, (1.0f + 2.0f + 0.5f * 4.0f) / 2.5f);
  EXPECT_FLOAT_EQ(two.at(1, 0).x, (0.5f * 4.0f + 8.0f + 16.0f) / 2.5f);
  ImageRgb three(1, 3);
  three.pixels = {Color(3.0f), Color(6.0f), Color(9.0f)};
  EXPECT_FLOAT_EQ(halved(three).at(0, 0).x, 6.0f);
}

TEST(MipPyramid, EveryLevelKeepsTheMeanDownToOneTexel) {
  for (const auto& [width, height] : {std::pair{16, 16}, std::pair{20, 12}, std::pair{7, 5}}) {
    const ImageRgb image = randomImage(width, height, 9);
    const std::vector<ImageRgb> levels = mipLevels(image);
    ASSERT_EQ(levels.back().width, 1);
    ASSERT_EQ(levels.back().height, 1);
    for (size_t i = 1; i < levels.size(); ++i) {
      EXPECT_EQ(levels[i].width, std::max(1, levels[i - 1].width / 2));
      EXPECT_EQ(levels[i].height, std::max(1, levels[i - 1].height / 2));
      const glm::dvec3 expected = mean(image), got = mean(levels[i]);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(got[c], expected[c], 1e-5 * std::max(1.0, expected[c]))
            << width << "x" << height << " level " << i;
      }
    }
  }
  EXPECT_EQ(mipLevels(randomImage(1024, 1024, 2)).size(), 11u);
  // 20x12 + 10x6 + 5x3 + 2x1 + 1x1.
  EXPECT_EQ(mipLevelsTexels(20, 12), 240u + 60u + 15u + 2u + 1u);
  EXPECT_EQ(mipLevelsTexels(1024, 1024), (uint64_t{1} << 22) / 3);  // (4^11 - 1) / 3
}

TEST(MipPyramid, BytePyramidsAreTheFloatPyramidRoundedToBytes) {
  // Level 0 keeps the bytes; each level above is the float pyramid of the decoded image, each
  // texel rounded to its nearest sRGB byte (not the bytes of rounded levels averaged again).
  for (const auto& [width, height] : {std::pair{16, 16}, std::pair{12, 7}}) {
    SrgbImage image{width, height, {}};
    Pcg32 rng(11, 4);
    for (int i = 0; i < 3 * width * height; ++i) {
      image.rgb.push_back(static_cast<uint8_t>(rng.nextUint() & 0xff));
    }
    const std::vector<SrgbTexels> bytes = srgbMipLevels(image);
    const std::vector<ImageRgb> floats = mipLevels(linearFromSrgb(image));
    ASSERT_EQ(bytes.size(), floats.size());
    EXPECT_EQ(bytes[0].texels, packedTexels(image).texels);
    for (size_t i = 1; i < bytes.size(); ++i) {
      EXPECT_EQ(bytes[i].width, floats[i].width);
      EXPECT_EQ(bytes[i].height, floats[i].height);
      EXPECT_EQ(bytes[i].texels, packedTexels(floats[i]).texels)
          << width << "x" << height << " level " << i;
    }
  }
}

}  // namespace
}  // namespace prism

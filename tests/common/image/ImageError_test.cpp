// Error metrics on synthetic images whose answers are known by hand.
#include "image/ImageError.h"

#include <gtest/gtest.h>

#include <cmath>

namespace prism {
namespace {

ImageRgb filled(int w, int h, float value) {
  ImageRgb image(w, h);
  for (Color& c : image.pixels) c = Color(value);
  return image;
}

TEST(ImageError, IdenticalImagesHaveNoErrorAndAllTheFlux) {
  ImageRgb reference = filled(4, 3, 0.5f);
  reference.at(1, 1) = Color(2.0f);
  const ImageRgb base = filled(4, 3, 0.5f);
  const ImageError e = imageError(reference, reference, base);
  EXPECT_EQ(e.pixels, 12u);
  EXPECT_EQ(e.rmse, 0.0);
  EXPECT_EQ(e.mrse, 0.0);
  EXPECT_EQ(e.maxError, 0.0);
  EXPECT_DOUBLE_EQ(e.fluxRatio, 1.0);
}

TEST(ImageError, AConstantOffsetGivesTheKnownNumbers) {
  const ImageRgb reference = filled(8, 8, 0.3f);
  const ImageRgb test = filled(8, 8, 0.4f);
  const ImageError e = imageError(test, reference);
  EXPECT_NEAR(e.rmse, 0.1, 1e-6);
  EXPECT_NEAR(e.relRmse, 0.1 / 0.3, 1e-5);
  EXPECT_NEAR(e.mrse, 0.01 / (0.09 + 0.01), 1e-5);  // (t − r)² / (r² + 0.01)
  EXPECT_NEAR(e.maxError, 0.1, 1e-6);
  EXPECT_TRUE(std::isnan(e.fluxRatio));  // no base frame given
}

TEST(ImageError, OneWrongChannelCountsAsAThirdOfThePixel) {
  const ImageRgb reference = filled(1, 1, 1.0f);
  ImageRgb test = reference;
  test.pixels[0].z = 4.0f;  // error 3 in one of three values
  const ImageError e = imageError(test, reference);
  EXPECT_NEAR(e.rmse, std::sqrt(9.0 / 3.0), 1e-6);
  EXPECT_NEAR(e.maxError, 3.0, 1e-6);
}

TEST(ImageError, FluxRatioIsTheCausticLightFoundOverTheCausticLightThere) {
  const ImageRgb base = filled(10, 1, 0.2f);
  ImageRgb reference = base, half = base, spread = base;
  for (int x = 4; x < 6; ++x) reference.at(x, 0) += Color(1.0f);  // 2 pixels of caustic
  for (int x = 4; x < 6; ++x) half.at(x, 0) += Color(0.5f);
  for (int x = 2; x < 8; ++x) spread.at(x, 0) += Color(1.0f / 3.0f);  // the same light, blurred
  EXPECT_NEAR(imageError(half, reference, base).fluxRatio, 0.5, 1e-6);
  EXPECT_NEAR(imageError(spread, reference, base).fluxRatio, 1.0, 1e-6);
  // Over the two caustic pixels only, the blurred image has a third of the light.
  PixelMask mask(10, 0);
  mask[4] = mask[5] = 1;
  const ImageError masked = imageError(spread, reference, base, mask);
  EXPECT_EQ(masked.pixels, 2u);
  EXPECT_NEAR(masked.fluxRatio, 1.0 / 3.0, 1e-6);
  EXPECT_NEAR(masked.maxError, 2.0 / 3.0, 1e-6);
  // A region that selects nothing has no numbers rather than perfect ones.
  const ImageError none = imageError(spread, reference, base, PixelMask(10, 0));
  EXPECT_EQ(none.pixels, 0u);
  EXPECT_TRUE(std::isnan(none.rmse));
  EXPECT_TRUE(std::isnan(none.fluxRatio));
}

TEST(ImageError, CausticMaskKeepsTheBrightCausticAndGrowsIt) {
  const ImageRgb base = filled(10, 10, 0.1f);
  ImageRgb reference = base;
  for (int y = 4; y < 6; ++y)
    for (int x = 4; x < 6; ++x) reference.at(x, y) += Color(1.0f);
  reference.at(0, 0) += Color(0.01f);  // faint, below 5 % of the caustic: left out
  const PixelMask tight = causticMask(reference, base, 0.05, 0);
  EXPECT_EQ(maskedPixels(tight), 4u);
  const PixelMask grown = causticMask(reference, base, 0.05, 1);
  EXPECT_EQ(maskedPixels(grown), 16u);
  EXPECT_TRUE(grown[3 * 10 + 3]);
  EXPECT_FALSE(grown[0]);
  EXPECT_EQ(maskedPixels(causticMask(base, base)), 0u);  // no caustic light: empty
}

TEST(ImageError, SizeMismatchIsRefusedWithBothSizes) {
  try {
    imageError(filled(2, 2, 0.0f), filled(3, 2, 0.0f));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "the test image is 2x2, the reference 3x2");
  }
}

}  // namespace
}  // namespace prism

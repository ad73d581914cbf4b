#include "image/ImageIo.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "image/ToneMap.h"
#include "master/PrismProcess.h"  // test::ScratchFolderTest

namespace prism {
namespace {

namespace fs = std::filesystem;

class ImageIoTest : public test::ScratchFolderTest {};

ImageRgb gradient() {
  ImageRgb image(7, 5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) image.at(x, y) = Color(x * 0.37f, y * 1.91f, 1e-4f * (x + y));
  return image;
}

TEST_F(ImageIoTest, ExrKeepsLinearRadianceExactly) {
  const ImageRgb image = gradient();
  const std::string path = (dir_ / "frame.exr").string();
  writeImage(image, path, 123.0f);  // exposure must not touch EXR
  const ImageRgb back = readImage(path);
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.height, 5);
  for (size_t i = 0; i < image.pixels.size(); ++i) EXPECT_EQ(back.pixels[i], image.pixels[i]);
}

TEST_F(ImageIoTest, PngIsExposedClampedAndSrgbEncoded) {
  ImageRgb image(3, 1);
  image.at(0, 0) = Color(0.5f);
  image.at(1, 0) = Color(7.0f);
  image.at(2, 0) = Color(0.0f);
  const std::string path = (dir_ / "frame.png").string();
  writeImage(image, path, 0.5f);
  const ImageRgb back = readImage(path);  // linearised again on read
  EXPECT_NEAR(back.at(0, 0).x, 0.25f, 0.005f);
  EXPECT_FLOAT_EQ(back.at(1, 0).x, 1.0f);
  EXPECT_FLOAT_EQ(back.at(2, 0).x, 0.0f);
}

TEST_F(ImageIoTest, LeavesNoTemporaryFileBehind) {
  writeImage(gradient(), (dir_ / "a.png").string());
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir_)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "a.png");
  }
  EXPECT_EQ(files, 1u);
}

TEST_F(ImageIoTest, FailedWriteLeavesNothingAndNamesTheFile) {
  const std::string path = (dir_ / "missing-folder" / "a.png").string();
  try {
    writeImage(gradient(), path);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("a.png"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
}

TEST_F(ImageIoTest, UnknownExtensionIsRefusedUpFront) {
  std::string why;
  EXPECT_FALSE(isWritableImagePath((dir_ / "a.xyz").string(), &why));
  EXPECT_NE(why.find(".xyz"), std::string::npos) << why;
  EXPECT_FALSE(isWritableImagePath((dir_ / "noextension").string(), &why));
  EXPECT_TRUE(isWritableImagePath((dir_ / "a.exr").string()));
}

TEST_F(ImageIoTest, ReadingAMissingOrCorruptImageNamesIt) {
  {
    std::ofstream out(dir_ / "bad.png", std::ios::binary);
    out << "\x89PNG\r\n\x1a\n broken";
  }
  {
    std::ofstream out(dir_ / "bad.exr", std::ios::binary);
    out << "v/1\x01 broken";
  }
  for (const char* name : {"nothing.png", "nothing.exr", "nothing.tif", "bad.png", "bad.exr"}) {
    const std::string path = (dir_ / name).string();
    try {
      readImage(path);
      ADD_FAILURE() << "expected an error for " << name;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("cannot read image '" + path + "'"), std::string::npos)
          << e.what();
    }
  }
}

// Display bytes land where the tone curve says: radiance at the centre of byte b's interval
// encodes to b, and reads back to b's linear value, b·(1/255) through the sRGB curve.
TEST_F(ImageIoTest, PngHoldsTheToneMappedBytesExactly) {
  const int bytes[] = {0, 1, 10, 64, 128, 200, 254, 255};
  ImageRgb image(8, 1);
  for (int i = 0; i < 8; ++i) {
    image.at(i, 0) = Color(srgbToLinear(bytes[i] / 255.0f) * 2.0f);  // exposure 0.5 below
  }
  const std::string path = (dir_ / "bytes.png").string();
  writeImage(image, path, 0.5f);
  const ImageRgb back = readImage(path);
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(back.at(i, 0).x, srgbToLinear(static_cast<float>(bytes[i]) * (1.0f / 255.0f)))
        << bytes[i];
  }
}

// OpenImageIO (the library that wrote and read these formats before) sees exactly the pixels
// libpng and OpenEXR write, and reads them to exactly the floats they read.
TEST_F(ImageIoTest, OpenImageIoReadsTheSamePixels) {
  ImageRgb image = gradient();
  image.at(3, 3) = Color(0.0031308f, 0.5f, 1e6f);
  for (const char* name : {"same.png", "same.exr"}) {
    const std::string path = (dir_ / name).string();
    writeImage(image, path, 0.7f);
    const ImageRgb lean = readImage(path), oiio = readImageWithOpenImageIo(path);
    ASSERT_EQ(lean.width, oiio.width);
    ASSERT_EQ(lean.height, oiio.height);
    for (size_t i = 0; i < lean.pixels.size(); ++i) EXPECT_EQ(lean.pixels[i], oiio.pixels[i]) << i;
  }
}

// PNGs from elsewhere: the sky cube map's faces (written by scripts/make_scene_assets.py).
TEST_F(ImageIoTest, CubeMapFacesReadAsOpenImageIoReadsThem) {
  for (const char* face : {"px", "nx", "py", "ny", "pz", "nz"}) {
    const std::string path = std::string(PRISM_SOURCE_DIR) + "/scenes/assets/sky/" + face + ".png";
    const ImageRgb lean = readImage(path), oiio = readImageWithOpenImageIo(path);
    ASSERT_EQ(lean.width, oiio.width);
    ASSERT_EQ(lean.pixels.size(), oiio.pixels.size());
    EXPECT_TRUE(lean.pixels == oiio.pixels) << face;
  }
}

TEST_F(ImageIoTest, MetadataRoundTripsInPngAndExr) {
  for (const char* name : {"m.png", "m.exr"}) {
    const std::string path = (dir_ / name).string();
    writeImage(gradient(), path, 1.0f, {{"PrismPartial", "5/9"}, {"ImageDescription", "five"}});
    EXPECT_EQ(readImageText(path, "PrismPartial"), "5/9") << name;
    EXPECT_EQ(readImageText(path, "ImageDescription"), "five") << name;
    EXPECT_EQ(readImageText(path, "Software"), "Prism") << name;
    EXPECT_EQ(readImageText(path, "Absent"), "") << name;
  }
}

TEST_F(ImageIoTest, OtherExtensionsAreWritableThroughOpenImageIo) {
  EXPECT_TRUE(isWritableImagePath((dir_ / "a.tif").string()));
  EXPECT_TRUE(isWritableImagePath((dir_ / "a.hdr").string()));
  EXPECT_TRUE(isWritableImagePath((dir_ / "a.PNG").string()));
}

TEST(ToneMap, SrgbCurveRoundTripsAndClamps) {
  for (float v : {0.0f, 0.001f, 0.0031308f, 0.2f, 0.5f, 1.0f}) {
    EXPECT_NEAR(srgbToLinear(linearToSrgb(v)), v, 1e-6f);
  }
  EXPECT_EQ(toDisplayByte(5.0f, 1.0f), 255);
  EXPECT_EQ(toDisplayByte(-1.0f, 1.0f), 0);
  EXPECT_EQ(toDisplayByte(std::nanf(""), 1.0f), 0);
  EXPECT_EQ(toDisplayByte(0.5f, 2.0f), 255);
}

TEST(ToneMap, TableEncoderMatchesTheFormula) {
  for (float exposure : {1.0f, 0.37f, 4.0f}) {
    const DisplayEncoder encode(exposure);
    int mismatches = 0;
    for (int i = 0; i <= 200000; ++i) {
      const float radiance = 1.2f * static_cast<float>(i) / 200000.0f;
      const int exact = toDisplayByte(radiance, exposure);
      const int fast = encode(radiance);
      ASSERT_LE(std::abs(exact - fast), 1) << radiance;
      mismatches += exact != fast;
    }
    // Only values within float rounding of a byte boundary may land on the other side.
    EXPECT_LT(mismatches, 20) << "exposure " << exposure;
  }
  const DisplayEncoder encode(1.0f);
  EXPECT_EQ(encode(-1.0f), 0);
  EXPECT_EQ(encode(std::nanf("")), 0);
  EXPECT_EQ(encode(1e30f), 255);
  EXPECT_EQ(encode(0.0f), 0);
  EXPECT_EQ(encode(1.0f), 255);
}

// The bucket table must give exactly the binary search's byte, or PNGs would change: every float
// near a threshold (one ulp either side) and a dense sweep of the whole range, for exposures
// from tiny to huge.
TEST(ToneMap, BucketTableMatchesTheBinarySearchExactly) {
  for (float exposure : {1.0f, 0.37f, 4.0f, 1e-3f, 1e3f, 0.7f}) {
    const DisplayEncoder encode(exposure);
    const float first = srgbToLinear(0.5f / 255.0f) / exposure;
    const float last = srgbToLinear(254.5f / 255.0f) / exposure;
    int checked = 0;
    for (int b = 1; b < 256; ++b) {
      const float t = srgbToLinear((static_cast<float>(b) - 0.5f) / 255.0f) / exposure;
      for (float v : {std::nextafter(t, 0.0f), t, std::nextafter(t, 1e30f)}) {
        ASSERT_EQ(encode(v), encode.encode(v)) << "exposure " << exposure << " value " << v;
        ++checked;
      }
    }
    const uint32_t from = std::bit_cast<uint32_t>(first * 0.5f);
    const uint32_t to = std::bit_cast<uint32_t>(last * 2.0f);
    for (uint32_t bits = from; bits < to; bits += 97) {
      const float v = std::bit_cast<float>(bits);
      ASSERT_EQ(encode(v), encode.encode(v)) << "exposure " << exposure << " value " << v;
      ++checked;
    }
    EXPECT_GT(checked, 1000000);
    for (float v : {0.0f, -0.0f, -1.0f, std::nanf(""), std::numeric_limits<float>::infinity(),
                    -std::numeric_limits<float>::infinity(), 1e-45f}) {
      EXPECT_EQ(encode(v), encode.encode(v)) << v;
    }
  }
}

}  // namespace
}  // namespace prism

#include "image/PngFile.h"

#include <gtest/gtest.h>
#include <png.h>

#include <filesystem>
#include <fstream>

#include "image/ToneMap.h"
#include "master/PrismProcess.h"  // test::ScratchFolderTest

namespace prism {
namespace {

namespace fs = std::filesystem;

class PngFileTest : public test::ScratchFolderTest {};

TEST_F(PngFileTest, BytesRoundTripExactlyForEveryEncoding) {
  // 5×3 pixels holding a spread of byte values, each channel different.
  std::vector<uint8_t> rgb(5 * 3 * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<uint8_t>((i * 37 + 11) % 256);
  for (int level : {0, 1, 3, 9}) {
    for (int filters : {PNG_FILTER_NONE, PNG_FILTER_SUB, PNG_FILTER_PAETH, PNG_ALL_FILTERS}) {
      writePng(path("a.png"), 5, 3, rgb.data(), {}, PngEncoding{level, filters});
      const std::optional<SrgbImage> back = readPng(path("a.png"));
      ASSERT_TRUE(back.has_value());
      EXPECT_EQ(back->width, 5);
      EXPECT_EQ(back->height, 3);
      EXPECT_EQ(back->rgb, rgb) << "level " << level << " filters " << filters;
    }
  }
}

TEST_F(PngFileTest, TextChunksRoundTripUnderOpenImageIosNames) {
  const uint8_t black[3] = {0, 0, 0};
  writePng(path("t.png"), 1, 1, black,
           {{"PrismPartial", "57/120"}, {"ImageDescription", "half done"}});
  EXPECT_EQ(readPngText(path("t.png"), "PrismPartial"), "57/120");
  EXPECT_EQ(readPngText(path("t.png"), "ImageDescription"), "half done");
  EXPECT_EQ(readPngText(path("t.png"), "Description"), "half done");  // PNG's own keyword
  EXPECT_EQ(readPngText(path("t.png"), "Software"), "Prism");
  EXPECT_EQ(readPngText(path("t.png"), "Nothing"), std::nullopt);
  EXPECT_EQ(readPngText(path("missing.png"), "Software"), std::nullopt);
}

TEST_F(PngFileTest, IsTaggedSrgb) {
  const uint8_t grey[3] = {128, 128, 128};
  writePng(path("s.png"), 1, 1, grey, {});
  std::ifstream in(path("s.png"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  // The sRGB chunk (rendering intent 3, absolute colorimetric, as OpenImageIO wrote it), and the
  // gAMA of 1/2.2 (45455 · 10⁻⁵) that older readers use instead.
  EXPECT_NE(bytes.find(std::string("sRGB\x03", 5)), std::string::npos);
  EXPECT_NE(bytes.find(std::string("gAMA\x00\x00\xb1\x8f", 8)), std::string::npos);
}

TEST_F(PngFileTest, GreyPngsReadAsRgb) {
  // A 2×1 8-bit grey PNG written with libpng's simplified API.
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = 2;
  image.height = 1;
  image.format = PNG_FORMAT_GRAY;
  const uint8_t grey[2] = {7, 200};
  ASSERT_TRUE(png_image_write_to_file(&image, path("g.png").c_str(), 0, grey, 0, nullptr));
  const std::optional<SrgbImage> back = readPng(path("g.png"));
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->rgb, (std::vector<uint8_t>{7, 7, 7, 200, 200, 200}));
}

TEST_F(PngFileTest, LeavesOtherKindsToOpenImageIo) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = 1;
  image.height = 1;
  image.format = PNG_FORMAT_RGBA;  // alpha: OpenImageIO's alpha handling applies
  const uint8_t rgba[4] = {1, 2, 3, 4};
  ASSERT_TRUE(png_image_write_to_file(&image, path("a.png").c_str(), 0, rgba, 0, nullptr));
  EXPECT_EQ(readPng(path("a.png")), std::nullopt);
}

TEST_F(PngFileTest, MissingAndCorruptFilesThrow) {
  EXPECT_THROW(readPng(path("missing.png")), std::runtime_error);
  {
    std::ofstream out(path("bad.png"), std::ios::binary);
    out << "\x89PNG\r\n\x1a\n this is no PNG";
  }
  try {
    readPng(path("bad.png"));
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_STRNE(e.what(), "");
  }
  // Cut short in the middle of the image data.
  std::vector<uint8_t> rgb(64 * 64 * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<uint8_t>(i * 7919 % 251);
  writePng(path("cut.png"), 64, 64, rgb.data(), {});
  fs::resize_file(path("cut.png"), fs::file_size(path("cut.png")) / 2);
  EXPECT_THROW(readPng(path("cut.png")), std::runtime_error);
}

TEST_F(PngFileTest, WritingIntoAMissingFolderThrows) {
  const uint8_t black[3] = {0, 0, 0};
  EXPECT_THROW(writePng(path("no/such/folder/a.png"), 1, 1, black, {}), std::runtime_error);
}

}  // namespace
}  // namespace prism

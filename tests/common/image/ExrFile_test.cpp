#include "image/ExrFile.h"

#include <OpenEXR/openexr.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

#include "image/ImageIo.h"
#include "master/PrismProcess.h"  // test::ScratchFolderTest

namespace prism {
namespace {

namespace fs = std::filesystem;

class ExrFileTest : public test::ScratchFolderTest {};

// Bit-exact comparison (NaN included).
bool sameBits(const ImageRgb& a, const ImageRgb& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

ImageRgb awkwardValues() {
  ImageRgb image(9, 37);  // more rows than one ZIP chunk (16), not a multiple of it
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      image.at(x, y) = Color(x * 0.37f + y, std::ldexp(1.0f, x - y), -1e-3f * x * y);
    }
  }
  image.at(0, 0) = Color(std::numeric_limits<float>::infinity(), 0.0f, -0.0f);
  image.at(1, 0) = Color(std::numeric_limits<float>::quiet_NaN(), 1e30f, 1e-40f);  // denormal
  return image;
}

TEST_F(ExrFileTest, FloatsRoundTripBitExactlyWithEveryCompression) {
  const ImageRgb image = awkwardValues();
  for (int compression : {EXR_COMPRESSION_NONE, EXR_COMPRESSION_RLE, EXR_COMPRESSION_ZIPS,
                          EXR_COMPRESSION_ZIP, EXR_COMPRESSION_PIZ}) {
    writeExr(path("a.exr"), image, {}, ExrEncoding{compression, 1});
    const std::optional<ImageRgb> back = readExr(path("a.exr"));
    ASSERT_TRUE(back.has_value());
    EXPECT_TRUE(sameBits(*back, image)) << "compression " << compression;
  }
}

// A row of a rendered frame whose single-scanline deflate comes out exactly as long as the raw
// row: OpenEXR 3.1 alone writes it as garbage (openexr#2306; ExrFile.cpp stores it raw).
TEST_F(ExrFileTest, ARowThatDeflatesToItsOwnSizeSurvivesZip) {
  const std::optional<ImageRgb> row =
      readExr(std::string(PRISM_TEST_DATA_DIR) + "/images/zip-same-size-row.exr");
  ASSERT_TRUE(row.has_value());
  ASSERT_EQ(row->height, 1);
  for (int compression : {EXR_COMPRESSION_ZIPS, EXR_COMPRESSION_ZIP}) {
    for (int level : {1, 4, 6}) {
      writeExr(path("row.exr"), *row, {}, ExrEncoding{compression, level});
      EXPECT_TRUE(sameBits(*readExr(path("row.exr")), *row))
          << "compression " << compression << " level " << level;
    }
  }
}

TEST_F(ExrFileTest, StringAttributesRoundTripUnderOpenImageIosNames) {
  writeExr(path("m.exr"), ImageRgb(2, 2),
           {{"PrismPartial", "3/4"}, {"ImageDescription", "three quarters"}});
  EXPECT_EQ(readExrText(path("m.exr"), "PrismPartial"), "3/4");
  EXPECT_EQ(readExrText(path("m.exr"), "ImageDescription"), "three quarters");
  EXPECT_EQ(readExrText(path("m.exr"), "comments"), "three quarters");  // OpenEXR's own name
  EXPECT_EQ(readExrText(path("m.exr"), "Software"), "Prism");
  EXPECT_EQ(readExrText(path("m.exr"), "DateTime")->size(), 19u);  // YYYY:MM:DD HH:MM:SS
  EXPECT_EQ(readExrText(path("m.exr"), "Nothing"), std::nullopt);
  EXPECT_EQ(readExrText(path("m.exr"), "dataWindow"), std::nullopt);  // not a string
  EXPECT_EQ(readExrText(path("missing.exr"), "Software"), std::nullopt);
}

// A 2×1 uncompressed scanline EXR of half-float channels, written chunk by chunk with OpenEXRCore
// (writeExr only writes float RGB). halves holds, per channel in name order, two half bit patterns.
void writeHalfExr(const std::string& path, const std::vector<const char*>& names,
                  const std::vector<std::array<uint16_t, 2>>& halves) {
  exr_context_t ctx = nullptr;
  ASSERT_EQ(exr_start_write(&ctx, path.c_str(), EXR_WRITE_FILE_DIRECTLY, nullptr), EXR_ERR_SUCCESS);
  int part = 0;
  ASSERT_EQ(exr_add_part(ctx, "", EXR_STORAGE_SCANLINE, &part), EXR_ERR_SUCCESS);
  ASSERT_EQ(exr_initialize_required_attr_simple(ctx, part, 2, 1, EXR_COMPRESSION_NONE),
            EXR_ERR_SUCCESS);
  for (const char* name : names) {
    ASSERT_EQ(exr_add_channel(ctx, part, name, EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1),
              EXR_ERR_SUCCESS);
  }
  ASSERT_EQ(exr_write_header(ctx), EXR_ERR_SUCCESS);
  // One scanline: each channel's two values in turn, little-endian (names are already sorted).
  std::vector<uint16_t> line;
  for (const auto& channel : halves) line.insert(line.end(), channel.begin(), channel.end());
  ASSERT_EQ(exr_write_scanline_chunk(ctx, part, 0, line.data(), line.size() * 2), EXR_ERR_SUCCESS);
  ASSERT_EQ(exr_finish(&ctx), EXR_ERR_SUCCESS);
}

constexpr uint16_t kHalfQuarter = 0x3400, kHalfHalf = 0x3800, kHalfOne = 0x3c00, kHalfTwo = 0x4000;

TEST_F(ExrFileTest, HalfChannelsReadAsTheirExactFloats) {
  writeHalfExr(path("h.exr"), {"B", "G", "R"},
               {{kHalfOne, kHalfHalf}, {kHalfQuarter, 0}, {kHalfHalf, kHalfTwo}});
  const std::optional<ImageRgb> image = readExr(path("h.exr"));
  ASSERT_TRUE(image.has_value());
  EXPECT_EQ(image->at(0, 0), Color(0.5f, 0.25f, 1.0f));
  EXPECT_EQ(image->at(1, 0), Color(2.0f, 0.0f, 0.5f));
  EXPECT_TRUE(sameBits(readImageWithOpenImageIo(path("h.exr")), *image));
}

TEST_F(ExrFileTest, OtherKindsAreLeftToOpenImageIo) {
  writeHalfExr(path("y.exr"), {"Y"}, {{kHalfHalf, kHalfTwo}});  // luminance only
  EXPECT_EQ(readExr(path("y.exr")), std::nullopt);
  const ImageRgb image = readImage(path("y.exr"));  // through OpenImageIO: one grey channel
  EXPECT_EQ(image.at(0, 0), Color(0.5f));
  EXPECT_EQ(image.at(1, 0), Color(2.0f));
}

TEST_F(ExrFileTest, MissingAndCorruptFilesThrow) {
  EXPECT_THROW(readExr(path("missing.exr")), std::runtime_error);
  {
    std::ofstream out(path("bad.exr"), std::ios::binary);
    out << "v/1\x01 not an EXR at all";
  }
  EXPECT_THROW(readExr(path("bad.exr")), std::runtime_error);
  writeExr(path("cut.exr"), awkwardValues(), {}, ExrEncoding{EXR_COMPRESSION_ZIP, 1});
  fs::resize_file(path("cut.exr"), fs::file_size(path("cut.exr")) - 40);
  EXPECT_THROW(readExr(path("cut.exr")), std::runtime_error);
}

TEST_F(ExrFileTest, WritingIntoAMissingFolderThrows) {
  EXPECT_THROW(writeExr(path("no/such/folder/a.exr"), ImageRgb(1, 1), {}), std::runtime_error);
}

}  // namespace
}  // namespace prism

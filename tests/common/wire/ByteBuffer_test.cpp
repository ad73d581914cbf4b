#include "wire/ByteBuffer.h"

#include "wire/FieldCodec.h"

#include <gtest/gtest.h>

#include <bit>
#include <limits>

namespace prism::wire {
namespace {

// Vectors of numbers and of strings go through the field codec (wire/FieldCodec.h), on the
// reader's count check.
template <class T>
std::vector<T> readVector(ByteReader& r) {
  std::vector<T> values;
  readField(r, values);
  return values;
}

TEST(ByteBuffer, WritesLittleEndianWhateverTheHost) {
  ByteWriter w;
  w.writeU16(0x0102);
  w.writeU32(0x01020304);
  w.writeU64(0x0102030405060708ull);
  w.writeI32(-2);
  w.writeF32(1.0f);  // 0x3F800000
  const std::vector<uint8_t> expected = {0x02, 0x01, 0x04, 0x03, 0x02, 0x01, 0x08, 0x07,
                                         0x06, 0x05, 0x04, 0x03, 0x02, 0x01, 0xFE, 0xFF,
                                         0xFF, 0xFF, 0x00, 0x00, 0x80, 0x3F};
  EXPECT_EQ(w.bytes(), expected);
}

TEST(ByteBuffer, RoundTripsEveryType) {
  ByteWriter w;
  w.writeU8(0xAB);
  w.writeU16(0xBEEF);
  w.writeU32(0xDEADBEEF);
  w.writeU64(0xFEEDFACECAFEBEEFull);
  w.writeI32(std::numeric_limits<int32_t>::min());
  w.writeF32(3.25f);
  w.writeF64(-1.0e300);
  w.writeBool(true);
  w.writeBool(false);
  w.writeString(std::string("nul\0inside", 10));
  w.writeString("");
  w.writeVec3(Vec3(1.5f, -2.5f, 3.5f));
  w.writeVec3s({Vec3(1, 2, 3), Vec3(4, 5, 6)});
  writeField(w, std::vector<uint32_t>{7, 8, 9, 0xFFFFFFFF});
  writeField(w, std::vector<std::string>{"a", "bc"});

  ByteReader r(w.bytes());
  EXPECT_EQ(r.readU8(), 0xAB);
  EXPECT_EQ(r.readU16(), 0xBEEF);
  EXPECT_EQ(r.readU32(), 0xDEADBEEFu);
  EXPECT_EQ(r.readU64(), 0xFEEDFACECAFEBEEFull);
  EXPECT_EQ(r.readI32(), std::numeric_limits<int32_t>::min());
  EXPECT_EQ(r.readF32(), 3.25f);
  EXPECT_EQ(r.readF64(), -1.0e300);
  EXPECT_TRUE(r.readBool());
  EXPECT_FALSE(r.readBool());
  EXPECT_EQ(r.readString(), std::string("nul\0inside", 10));
  EXPECT_EQ(r.readString(), "");
  EXPECT_EQ(r.readVec3(), Vec3(1.5f, -2.5f, 3.5f));
  EXPECT_EQ(r.readVec3s(), (std::vector<Vec3>{Vec3(1, 2, 3), Vec3(4, 5, 6)}));
  EXPECT_EQ(readVector<uint32_t>(r), (std::vector<uint32_t>{7, 8, 9, 0xFFFFFFFF}));
  EXPECT_EQ(readVector<std::string>(r), (std::vector<std::string>{"a", "bc"}));
  EXPECT_EQ(r.remaining(), 0u);
  EXPECT_NO_THROW(r.expectEnd());
}

TEST(ByteBuffer, FloatsTravelAsBitPatterns) {
  const float floats[] = {-0.0f, std::numeric_limits<float>::denorm_min(),
                          std::numeric_limits<float>::infinity(),
                          std::bit_cast<float>(0x7FC01234u)};  // NaN with a payload
  const double doubles[] = {-0.0, std::numeric_limits<double>::denorm_min(),
                            std::bit_cast<double>(0xFFF8000000ABCDEFull)};
  ByteWriter w;
  for (float f : floats) w.writeF32(f);
  for (double d : doubles) w.writeF64(d);
  ByteReader r(w.bytes());
  for (float f : floats)
    EXPECT_EQ(std::bit_cast<uint32_t>(r.readF32()), std::bit_cast<uint32_t>(f));
  for (double d : doubles) {
    EXPECT_EQ(std::bit_cast<uint64_t>(r.readF64()), std::bit_cast<uint64_t>(d));
  }
}

TEST(ByteBuffer, OverrunNamesTheOffsetAndWhatIsLeft) {
  const std::vector<uint8_t> bytes(12, 0);
  ByteReader r(bytes);
  r.readU64();
  try {
    r.readU64();
    FAIL() << "reading past the end did not throw";
  } catch (const WireError& e) {
    EXPECT_STREQ(e.what(), "truncated message: needed 8 bytes at offset 8, 4 left");
  }
  EXPECT_EQ(r.offset(), 8u);  // a failed read consumes nothing
  EXPECT_EQ(r.readU32(), 0u);
  EXPECT_THROW(r.readU8(), WireError);
}

TEST(ByteBuffer, EveryReadOfAnEmptyBufferThrows) {
  ByteReader r(nullptr, 0);
  EXPECT_THROW(r.readU8(), WireError);
  EXPECT_THROW(r.readU16(), WireError);
  EXPECT_THROW(r.readU32(), WireError);
  EXPECT_THROW(r.readU64(), WireError);
  EXPECT_THROW(r.readI32(), WireError);
  EXPECT_THROW(r.readF32(), WireError);
  EXPECT_THROW(r.readF64(), WireError);
  EXPECT_THROW(r.readBool(), WireError);
  EXPECT_THROW(r.readString(), WireError);
  EXPECT_THROW(r.readVec3(), WireError);
  EXPECT_THROW(r.readVec3s(), WireError);
  EXPECT_THROW(readVector<uint32_t>(r), WireError);
  EXPECT_NO_THROW(r.expectEnd());
}

TEST(ByteBuffer, ExpectEndRejectsTrailingBytes) {
  const std::vector<uint8_t> bytes = {1, 2, 3};
  ByteReader r(bytes);
  r.readU16();
  try {
    r.expectEnd();
    FAIL() << "trailing byte accepted";
  } catch (const WireError& e) {
    EXPECT_STREQ(e.what(), "unexpected trailing data: 1 bytes left after offset 2");
  }
}

TEST(ByteBuffer, BoolsOtherThanZeroOrOneAreRejected) {
  const std::vector<uint8_t> bytes = {2};
  ByteReader r(bytes);
  EXPECT_THROW(r.readBool(), WireError);
}

TEST(ByteBuffer, StringLongerThanTheMessageIsRejected) {
  ByteWriter w;
  w.writeU32(0xFFFFFFFF);
  w.writeString("abc");
  ByteReader r(w.bytes());
  EXPECT_THROW(r.readString(), WireError);
}

// A corrupted count must be refused by comparing it with the bytes left, not by trying (and
// failing, or worse succeeding) to allocate 2^60 elements.
TEST(ByteBuffer, HugeCountsThrowWithoutAllocating) {
  for (uint64_t count : {uint64_t{1} << 60, ~uint64_t{0}, uint64_t{9}}) {
    ByteWriter w;
    w.writeU64(count);
    w.writeU64(0);
    ByteReader vec3s(w.bytes());
    EXPECT_THROW(vec3s.readVec3s(), WireError) << count;
    ByteReader u32s(w.bytes());
    EXPECT_THROW(readVector<uint32_t>(u32s), WireError) << count;
    ByteReader strings(w.bytes());
    EXPECT_THROW(readVector<std::string>(strings), WireError) << count;
  }
}

TEST(ByteBuffer, CountCheckAllowsExactlyWhatFits) {
  ByteWriter w;
  w.writeU64(2);
  w.writeU64(0);
  ByteReader r(w.bytes());
  EXPECT_EQ(r.readCount(4), 2u);
  ByteReader tooMany(w.bytes());
  EXPECT_THROW(tooMany.readCount(5), WireError);
}

}  // namespace
}  // namespace prism::wire

#include "wire/ByteBuffer.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "util/HugePages.h"

namespace prism::wire {

void ByteWriter::writeLittleEndian(uint64_t v, int byteCount) {
  for (int i = 0; i < byteCount; ++i) bytes_.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

// Floats travel as their bit patterns, so values (NaN payloads and -0 included) arrive exactly.
void ByteWriter::writeF32(float v) {
  writeU32(std::bit_cast<uint32_t>(v));
}

void ByteWriter::writeF64(double v) {
  writeU64(std::bit_cast<uint64_t>(v));
}

void ByteWriter::writeString(const std::string& s) {
  if (s.size() > UINT32_MAX)
    throw WireError("string of " + std::to_string(s.size()) +
                    " bytes is too long for the wire format");
  writeU32(static_cast<uint32_t>(s.size()));
  bytes_.insert(bytes_.end(), s.begin(), s.end());
}

void ByteWriter::writeVec3(const Vec3& v) {
  writeF32(v.x);
  writeF32(v.y);
  writeF32(v.z);
}

namespace {

// Meshes (12 bytes per vertex and per triangle, 85 MiB for 5 M triangles) are copied in one go
// instead of byte by byte where the wire order is native.
static_assert(sizeof(Vec3) == 3 * sizeof(float), "Vec3 must be three packed floats");

}  // namespace

void ByteWriter::reserveMore(size_t more) {
  if (bytes_.capacity() >= bytes_.size() + more) return;
  bytes_.reserve(bytes_.size() + more);
  preferHugePages(bytes_.data(), bytes_.capacity());
}

void ByteWriter::appendRaw(const void* data, size_t size) {
  if (size == 0) return;  // an empty vector's data() may be null, which memcpy must not see
  const size_t at = bytes_.size();
  if (bytes_.capacity() < at + size) {
    bytes_.reserve(std::max(at + size, 2 * bytes_.capacity()));
    preferHugePages(bytes_.data(), bytes_.capacity());
  }
  // Inserted, not resized and copied over: one pass over the bytes instead of two.
  const auto* from = static_cast<const uint8_t*>(data);
  bytes_.insert(bytes_.end(), from, from + size);
}

void ByteWriter::writeVec3s(const std::vector<Vec3>& v) {
  writeCount(v.size());
  if constexpr (kWireOrderIsNative) {
    appendRaw(v.data(), v.size() * sizeof(Vec3));
  } else {
    for (const Vec3& e : v) writeVec3(e);
  }
}

void ByteWriter::writeU8s(const std::vector<uint8_t>& v) {
  writeCount(v.size());
  bytes_.insert(bytes_.end(), v.begin(), v.end());
}

void ByteReader::readRaw(void* out, size_t size) {
  need(size);
  if (size == 0) return;  // out may be null then, which memcpy must not see
  std::memcpy(out, data_ + offset_, size);
  offset_ += size;
}

void ByteReader::need(size_t n) const {
  if (n > remaining()) {
    throw WireError("truncated message: needed " + std::to_string(n) + " bytes at offset " +
                    std::to_string(offset_) + ", " + std::to_string(remaining()) + " left");
  }
}

uint64_t ByteReader::readLittleEndian(int byteCount) {
  need(static_cast<size_t>(byteCount));
  uint64_t v = 0;
  for (int i = 0; i < byteCount; ++i) v |= static_cast<uint64_t>(data_[offset_ + i]) << (8 * i);
  offset_ += static_cast<size_t>(byteCount);
  return v;
}

float ByteReader::readF32() {
  return std::bit_cast<float>(readU32());
}

double ByteReader::readF64() {
  return std::bit_cast<double>(readU64());
}

bool ByteReader::readBool() {
  const size_t at = offset_;
  const uint8_t v = readU8();
  if (v > 1) {
    throw WireError("invalid bool value " + std::to_string(v) + " at offset " + std::to_string(at));
  }
  return v == 1;
}

std::string ByteReader::readString() {
  const size_t length = readU32();
  need(length);
  std::string s(reinterpret_cast<const char*>(data_ + offset_), length);
  offset_ += length;
  return s;
}

Vec3 ByteReader::readVec3() {
  const float x = readF32();
  const float y = readF32();
  const float z = readF32();
  return Vec3(x, y, z);
}

size_t ByteReader::readCount(size_t minElementBytes) {
  const size_t at = offset_;
  const uint64_t count = readU64();
  // Divide rather than multiply: count * minElementBytes can overflow.
  const size_t perElement = minElementBytes > 0 ? minElementBytes : 1;
  if (count > remaining() / perElement) {
    throw WireError("corrupt element count " + std::to_string(count) + " at offset " +
                    std::to_string(at) + ": " + std::to_string(perElement) +
                    "-byte elements, but only " + std::to_string(remaining()) + " bytes left");
  }
  return static_cast<size_t>(count);
}

// count (checked against what is left), then count elements of T's size: copied in one go where
// the wire order is the machine's, else read one by one.
template <typename T, typename ReadOne>
std::vector<T> ByteReader::readArray(ReadOne readOne) {
  const size_t count = readCount(sizeof(T));
  std::vector<T> v;
  reserveOnHugePages(v, count);
  if constexpr (kWireOrderIsNative) {
    if (count == 0) return v;  // nothing to copy, and memcpy must not see a null pointer
    v.resize(count);
    std::memcpy(v.data(), data_ + offset_, count * sizeof(T));
    offset_ += count * sizeof(T);
  } else {
    for (size_t i = 0; i < count; ++i) v.push_back(readOne());
  }
  return v;
}

std::vector<Vec3> ByteReader::readVec3s() {
  return readArray<Vec3>([this] { return readVec3(); });
}

std::vector<uint8_t> ByteReader::readU8s() {
  return readArray<uint8_t>([this] { return readU8(); });
}

void ByteReader::expectEnd() const {
  if (remaining() != 0) {
    throw WireError("unexpected trailing data: " + std::to_string(remaining()) +
                    " bytes left after offset " + std::to_string(offset_));
  }
}

}  // namespace prism::wire

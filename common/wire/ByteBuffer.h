// Byte-level encoding for the wire format: fixed-width little-endian integers, IEEE floats by
// bit pattern, length-prefixed strings and counted sequences. The byte order is explicit so
// ranks on hosts of different endianness agree; the reader checks every length against what is
// left before it reads or allocates, so a corrupted message throws instead of crashing.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "math/Vec.h"

namespace prism::wire {

// Thrown for any malformed, truncated or unexpected message.
class WireError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// On a little-endian machine a value's bytes in memory are its wire form (numbers are written
// little-endian): arrays of packed numbers are copied in one go instead of number by number.
inline constexpr bool kWireOrderIsNative = std::endian::native == std::endian::little;

class ByteWriter {
 public:
  void writeU8(uint8_t v) { bytes_.push_back(v); }
  void writeU16(uint16_t v) { writeLittleEndian(v, 2); }
  void writeU32(uint32_t v) { writeLittleEndian(v, 4); }
  void writeU64(uint64_t v) { writeLittleEndian(v, 8); }
  void writeI32(int32_t v) { writeU32(static_cast<uint32_t>(v)); }
  void writeF32(float v);
  void writeF64(double v);
  void writeBool(bool v) { writeU8(v ? 1 : 0); }
  void writeString(const std::string& s);  // u32 length, then the bytes
  void writeVec3(const Vec3& v);           // also Color, which is the same type
  void writeCount(size_t n) { writeU64(n); }
  void writeVec3s(const std::vector<Vec3>& v);
  void writeU8s(const std::vector<uint8_t>& v);
  // Bytes as they are in memory: only for values whose memory is their wire form
  // (kWireOrderIsNative, no padding).
  void writeRaw(const void* data, size_t size) { appendRaw(data, size); }

  // Room for `more` bytes beyond what is written, so a large message grows in place instead of
  // being copied at every doubling.
  void reserveMore(size_t more);

  const std::vector<uint8_t>& bytes() const { return bytes_; }
  std::vector<uint8_t> take() { return std::move(bytes_); }
  // Writes into `reuse` from its start, keeping its memory: a writer for message after
  // message without a fresh (and page-faulted) buffer each time.
  void reuse(std::vector<uint8_t>&& buffer) {
    bytes_ = std::move(buffer);
    bytes_.clear();
  }
  // The last `count` bytes written, to be transformed in place (a filter over what was copied).
  uint8_t* lastBytes(size_t count) { return bytes_.data() + (bytes_.size() - count); }

 private:
  void writeLittleEndian(uint64_t v, int byteCount);
  void appendRaw(const void* data, size_t size);  // bytes as they are in memory

  std::vector<uint8_t> bytes_;
};

class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  explicit ByteReader(const std::vector<uint8_t>& bytes) : ByteReader(bytes.data(), bytes.size()) {}

  uint8_t readU8() { return static_cast<uint8_t>(readLittleEndian(1)); }
  uint16_t readU16() { return static_cast<uint16_t>(readLittleEndian(2)); }
  uint32_t readU32() { return static_cast<uint32_t>(readLittleEndian(4)); }
  uint64_t readU64() { return readLittleEndian(8); }
  int32_t readI32() { return static_cast<int32_t>(readU32()); }
  float readF32();
  double readF64();
  bool readBool();  // only 0 and 1 are valid
  std::string readString();
  Vec3 readVec3();
  // Reads a u64 element count and checks that count elements of at least minElementBytes each
  // fit in what is left, so a corrupted count is refused before anything is allocated.
  size_t readCount(size_t minElementBytes);
  std::vector<Vec3> readVec3s();
  std::vector<uint8_t> readU8s();
  // size bytes into out as they are (see ByteWriter::writeRaw).
  void readRaw(void* out, size_t size);

  size_t offset() const { return offset_; }
  size_t remaining() const { return size_ - offset_; }
  // Throws unless every byte has been read: trailing bytes mean the two sides disagree.
  void expectEnd() const;

 private:
  // Throws WireError unless n more bytes are available.
  void need(size_t n) const;
  template <typename T, typename ReadOne>
  std::vector<T> readArray(ReadOne readOne);
  uint64_t readLittleEndian(int byteCount);

  const uint8_t* data_;
  size_t size_;
  size_t offset_ = 0;
};

}  // namespace prism::wire

// The values of a PLY body, one at a time, in the order the header declares them: from text
// (AsciiPlyBody) or from bytes in either order (BinaryPlyBody). Both throw PlyBodyFailure for a
// value that is missing or malformed; the reader adds which element it was reading.
#pragma once

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "parse/PlyHeader.h"
#include "parse/PrintableText.h"
#include "util/FileLoc.h"

namespace prism {

struct PlyBodyFailure {
  std::string message;
};

inline bool isPlyIntegerType(PlyType type) {
  return type != PlyType::Float32 && type != PlyType::Float64;
}

// Whether value fits the integer type.
inline bool fitsPlyType(int64_t value, PlyType type) {
  switch (type) {
    case PlyType::Int8:
      return value >= INT8_MIN && value <= INT8_MAX;
    case PlyType::UInt8:
      return value >= 0 && value <= UINT8_MAX;
    case PlyType::Int16:
      return value >= INT16_MIN && value <= INT16_MAX;
    case PlyType::UInt16:
      return value >= 0 && value <= UINT16_MAX;
    case PlyType::Int32:
      return value >= INT32_MIN && value <= INT32_MAX;
    case PlyType::UInt32:
      return value >= 0 && value <= UINT32_MAX;
    default:
      return true;
  }
}

template <bool BigEndian>
class BinaryPlyBody {
 public:
  static constexpr bool kBinary = true;

  BinaryPlyBody(std::string_view bytes, size_t bodyOffset, std::string path)
      : begin_(bytes.data()),
        p_(bytes.data() + bodyOffset),
        end_(bytes.data() + bytes.size()),
        path_(std::move(path)) {}

  // A value of type T at `at`, in the body's byte order.
  template <class T>
  static T decode(const char* at) {
    T value;
    if constexpr ((std::endian::native == std::endian::big) == BigEndian || sizeof(T) == 1) {
      std::memcpy(&value, at, sizeof(T));
    } else {
      char reversed[sizeof(T)];
      for (size_t i = 0; i < sizeof(T); ++i) reversed[i] = at[sizeof(T) - 1 - i];
      std::memcpy(&value, reversed, sizeof(T));
    }
    return value;
  }
  // A value of the type at `at`, as a double (every PLY type fits one exactly).
  static double decodeNumber(PlyType type, const char* at) {
    switch (type) {
      case PlyType::Int8:
        return decode<int8_t>(at);
      case PlyType::UInt8:
        return decode<uint8_t>(at);
      case PlyType::Int16:
        return decode<int16_t>(at);
      case PlyType::UInt16:
        return decode<uint16_t>(at);
      case PlyType::Int32:
        return decode<int32_t>(at);
      case PlyType::UInt32:
        return decode<uint32_t>(at);
      case PlyType::Float32:
        return decode<float>(at);
      case PlyType::Float64:
        return decode<double>(at);
    }
    return 0.0;
  }

  double number(PlyType type) {
    const auto n = static_cast<size_t>(plyTypeBytes(type));
    need(n);
    const double value = decodeNumber(type, p_);
    p_ += n;
    return value;
  }
  // Only called for integer types (the reader checks the header), whose values fit.
  int64_t integer(PlyType type) { return static_cast<int64_t>(number(type)); }
  void skip(PlyType type) {
    const auto n = static_cast<size_t>(plyTypeBytes(type));
    need(n);
    p_ += n;
  }

  // For readers that take a run of fixed-size elements at once.
  const char* cursor() const { return p_; }
  size_t remaining() const { return static_cast<size_t>(end_ - p_); }
  void advance(size_t n) { p_ += n; }

  // Where a failure is reported: the file (a binary body has no lines), and the byte.
  FileLoc loc() const { return FileLoc{path_, 0, 0}; }
  std::string position() const { return " (byte " + std::to_string(p_ - begin_) + ")"; }

 private:
  void need(size_t n) const {
    if (static_cast<size_t>(end_ - p_) < n) throw PlyBodyFailure{"the file ends inside it"};
  }

  const char* begin_;
  const char* p_;
  const char* end_;
  std::string path_;
};

class AsciiPlyBody {
 public:
  static constexpr bool kBinary = false;

  AsciiPlyBody(std::string_view bytes, size_t bodyOffset, int bodyLine, std::string path)
      : p_(bytes.data() + bodyOffset),
        end_(bytes.data() + bytes.size()),
        lineStart_(p_),
        word_(p_),
        line_(bodyLine),
        path_(std::move(path)) {}

  double number(PlyType type) {
    const std::string_view word = next();
    if (isPlyIntegerType(type)) return static_cast<double>(checkedInteger(word, type));
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc() || ptr != word.data() + word.size()) {
      throw PlyBodyFailure{"expected a number but found '" + printableExcerpt(word) + "'"};
    }
    return value;
  }
  int64_t integer(PlyType type) { return checkedInteger(next(), type); }
  void skip(PlyType type) { number(type); }
  FileLoc loc() const { return FileLoc{path_, line_, static_cast<int>(word_ - lineStart_) + 1}; }
  std::string position() const { return ""; }

 private:
  std::string_view next() {
    for (;;) {
      while (p_ < end_ && (*p_ == ' ' || *p_ == '\t')) ++p_;
      if (p_ == end_) {
        word_ = p_;
        throw PlyBodyFailure{"the file ends inside it"};
      }
      if (*p_ != '\n' && *p_ != '\r') break;
      p_ += (*p_ == '\r' && p_ + 1 < end_ && p_[1] == '\n') ? 2 : 1;
      ++line_;
      lineStart_ = p_;
    }
    word_ = p_;
    while (p_ < end_ && *p_ != ' ' && *p_ != '\t' && *p_ != '\n' && *p_ != '\r') ++p_;
    return std::string_view(word_, static_cast<size_t>(p_ - word_));
  }
  static int64_t checkedInteger(std::string_view word, PlyType type) {
    int64_t value = 0;
    const auto [ptr, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc() || ptr != word.data() + word.size() || !fitsPlyType(value, type)) {
      throw PlyBodyFailure{"expected an integer of the declared type but found '" +
                           printableExcerpt(word) + "'"};
    }
    return value;
  }

  const char* p_;
  const char* end_;
  const char* lineStart_;
  const char* word_;  // the last word read, for error columns
  int line_;
  std::string path_;
};

}  // namespace prism

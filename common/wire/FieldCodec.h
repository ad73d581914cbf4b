// The wire form of a described struct (wire/Fields.h), from its field list: writeFields,
// readFields and sameFields, and the overloads they use, one per kind of field. The reader
// checks what each kind of field can check by itself (bounded counts, bools, enumerators), then
// each struct's own check() once its fields are read.
#pragma once

#include <algorithm>
#include <array>
#include <cstring>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "util/HugePages.h"
#include "wire/ByteBuffer.h"
#include "wire/Fields.h"
#include "wire/WireEnums.h"

namespace prism::wire {

// A vector of these travels as its memory, copied in one go: numbers on a little-endian machine,
// Vec3 (three packed floats), and described structs that declare kMemoryIsWireForm (no padding,
// every field a number: a photon), in their own list or in Fields<T>.
template <class T>
inline constexpr bool kMemoryIsWireForm = kWireOrderIsNative &&
                                          ((std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) ||
                                           std::is_same_v<T, Vec3> || std::is_same_v<T, Vec2> ||
                                           requires { requires Fields<T>::kMemoryIsWireForm; } ||
                                           requires { requires T::kMemoryIsWireForm; });
static_assert(sizeof(Vec3) == 3 * sizeof(float), "Vec3 must be three packed floats");
static_assert(sizeof(Vec2) == 2 * sizeof(float), "Vec2 must be two packed floats");

// Elements of a vector read in one go are checked this many at a time (28 KiB of photons).
inline constexpr size_t kCheckBlock = 1024;

struct NoCheck {
  void operator()(const auto&, size_t) const {}
};

template <class T>
concept Number = std::is_arithmetic_v<T>;
template <class T>
concept Enumeration = std::is_enum_v<T>;
template <class T>
concept DescribedStruct = Described<T> && !CustomField<T>;

// ---- writing --------------------------------------------------------------------------------

template <Number T>
void writeField(ByteWriter& w, T v) {
  if constexpr (std::is_same_v<T, bool>) {
    w.writeBool(v);
  } else if constexpr (std::is_same_v<T, float>) {
    w.writeF32(v);
  } else if constexpr (std::is_same_v<T, double>) {
    w.writeF64(v);
  } else if constexpr (sizeof(T) == 1) {
    w.writeU8(static_cast<uint8_t>(v));
  } else if constexpr (sizeof(T) == 2) {
    w.writeU16(static_cast<uint16_t>(v));
  } else if constexpr (sizeof(T) == 4) {
    w.writeU32(static_cast<uint32_t>(v));
  } else {
    static_assert(sizeof(T) == 8, "integers travel as 1, 2, 4 or 8 bytes");
    w.writeU64(static_cast<uint64_t>(v));
  }
}

template <Enumeration E>
void writeField(ByteWriter& w, E v) {
  w.writeU32(static_cast<uint32_t>(v));
}

inline void writeField(ByteWriter& w, const std::string& v) {
  w.writeString(v);
}

inline void writeField(ByteWriter& w, const Vec3& v) {
  w.writeVec3(v);
}

inline void writeField(ByteWriter& w, const Vec2& v) {
  writeField(w, v.x);
  writeField(w, v.y);
}

template <class T, size_t N>
void writeField(ByteWriter& w, const std::array<T, N>& values);
template <class T, size_t N>
void writeField(ByteWriter& w, const T (&values)[N]);
template <class T>
void writeField(ByteWriter& w, const std::optional<T>& value);
template <class T>
void writeField(ByteWriter& w, const std::vector<T>& values);
template <class B>
void writeField(ByteWriter& w, const Flag<B>& flag);
template <class V, class Check>
void writeField(ByteWriter& w, const Each<V, Check>& checked);
template <CustomField T>
void writeField(ByteWriter& w, const T& custom);
template <DescribedStruct T>
void writeField(ByteWriter& w, const T& value);

template <class T, size_t N>
void writeField(ByteWriter& w, const std::array<T, N>& values) {
  for (const T& v : values) writeField(w, v);
}

template <class T, size_t N>
void writeField(ByteWriter& w, const T (&values)[N]) {
  for (const T& v : values) writeField(w, v);
}

template <class T>
void writeField(ByteWriter& w, const std::optional<T>& value) {
  w.writeBool(value.has_value());
  if (value) writeField(w, *value);
}

template <class T>
void writeField(ByteWriter& w, const std::vector<T>& values) {
  w.writeCount(values.size());
  if constexpr (kMemoryIsWireForm<T>) {
    w.writeRaw(values.data(), values.size() * sizeof(T));
  } else {
    for (const T& v : values) writeField(w, v);
  }
}

template <class B>
void writeField(ByteWriter& w, const Flag<B>& flag) {
  w.writeBool(flag.value);
}

template <class V, class Check>
void writeField(ByteWriter& w, const Each<V, Check>& checked) {
  writeField(w, checked.values);
}

template <CustomField T>
void writeField(ByteWriter& w, const T& custom) {
  custom.write(w);
}

template <DescribedStruct T>
void writeField(ByteWriter& w, const T& value) {
  visitFields(value, [&w](const auto&... field) { (writeField(w, field), ...); });
}

// ---- reading --------------------------------------------------------------------------------

template <Number T>
void readField(ByteReader& r, T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    v = r.readBool();
  } else if constexpr (std::is_same_v<T, float>) {
    v = r.readF32();
  } else if constexpr (std::is_same_v<T, double>) {
    v = r.readF64();
  } else if constexpr (sizeof(T) == 1) {
    v = static_cast<T>(r.readU8());
  } else if constexpr (sizeof(T) == 2) {
    v = static_cast<T>(r.readU16());
  } else if constexpr (sizeof(T) == 4) {
    v = static_cast<T>(r.readU32());
  } else {
    v = static_cast<T>(r.readU64());
  }
}

// Any value but an enumerator would fall through every switch in the renderer. The cast keeps
// only the low bits for a narrower enumeration (CausticRole and DebugView are bytes), so 256
// would otherwise read as 0 (found by the wire fuzzer); scoped enumerations have a fixed
// underlying type, so the cast itself is well defined.
template <Enumeration E>
void readField(ByteReader& r, E& v) {
  const size_t at = r.offset();
  const uint32_t raw = r.readU32();
  v = static_cast<E>(raw);
  if (static_cast<uint32_t>(v) != raw || !isKnown(v)) {
    throw WireError("invalid " + std::string(enumName(v)) + " " + std::to_string(raw) +
                    " at offset " + std::to_string(at));
  }
}

inline void readField(ByteReader& r, std::string& v) {
  v = r.readString();
}

inline void readField(ByteReader& r, Vec3& v) {
  v = r.readVec3();
}

inline void readField(ByteReader& r, Vec2& v) {
  readField(r, v.x);
  readField(r, v.y);
}

template <class T, size_t N>
void readField(ByteReader& r, std::array<T, N>& values);
template <class T, size_t N>
void readField(ByteReader& r, T (&values)[N]);
template <class T>
void readField(ByteReader& r, std::optional<T>& value);
template <class T>
void readField(ByteReader& r, std::vector<T>& values);
template <class B>
void readField(ByteReader& r, Flag<B> flag);
template <class V, class Check>
void readField(ByteReader& r, Each<V, Check> checked);
template <CustomField T>
void readField(ByteReader& r, T& custom);
template <DescribedStruct T>
void readField(ByteReader& r, T& value);

template <class T, size_t N>
void readField(ByteReader& r, std::array<T, N>& values) {
  for (T& v : values) readField(r, v);
}

template <class T, size_t N>
void readField(ByteReader& r, T (&values)[N]) {
  for (T& v : values) readField(r, v);
}

template <class T>
void readField(ByteReader& r, std::optional<T>& value) {
  if (r.readBool()) {
    readField(r, value.emplace());
  } else {
    value.reset();
  }
}

// A count checked against the bytes left, then the elements. Values whose memory is their wire
// form are copied in one go (checked a block at a time); others grow the vector only as they
// actually decode, so its memory stays proportional to the message.
template <class T, class Check>
void readElements(ByteReader& r, std::vector<T>& values, const Check& check) {
  if constexpr (kMemoryIsWireForm<T>) {
    const size_t count = r.readCount(sizeof(T));
    std::vector<T> read;
    reserveOnHugePages(read, count);
    read.resize(count);
    if constexpr (std::is_same_v<Check, NoCheck>) {
      r.readRaw(read.data(), count * sizeof(T));
    } else {
      for (size_t first = 0; first < count; first += kCheckBlock) {
        const size_t end = std::min(count, first + kCheckBlock);
        r.readRaw(read.data() + first, (end - first) * sizeof(T));
        for (size_t i = first; i < end; ++i) check(read[i], i);
      }
    }
    values = std::move(read);
  } else {
    const size_t count = r.readCount(1);
    values.clear();
    for (size_t i = 0; i < count; ++i) {
      T element{};
      readField(r, element);
      check(std::as_const(element), i);
      values.push_back(std::move(element));
    }
  }
}

template <class T>
void readField(ByteReader& r, std::vector<T>& values) {
  readElements(r, values, NoCheck{});
}

template <class B>
void readField(ByteReader& r, Flag<B> flag) {
  const uint8_t raw = r.readU8();
  if (raw > 1) throw WireError("invalid " + std::string(flag.what) + " " + std::to_string(raw));
  flag.value = raw == 1;
}

template <class V, class Check>
void readField(ByteReader& r, Each<V, Check> checked) {
  readElements(r, checked.values, checked.check);
}

template <CustomField T>
void readField(ByteReader& r, T& custom) {
  custom.read(r);
}

template <DescribedStruct T>
void readField(ByteReader& r, T& value) {
  visitFields(value, [&r](auto&&... field) { (readField(r, field), ...); });
  checkFields(std::as_const(value));
}

// ---- equality: floats by bit pattern, so -0, denormals and NaNs compare as they travel ------

template <Number T>
bool sameField(T a, T b) {
  if constexpr (std::is_floating_point_v<T>) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
  } else {
    return a == b;
  }
}

template <Enumeration E>
bool sameField(E a, E b) {
  return a == b;
}

inline bool sameField(const std::string& a, const std::string& b) {
  return a == b;
}

inline bool sameField(const Vec3& a, const Vec3& b) {
  return sameField(a.x, b.x) && sameField(a.y, b.y) && sameField(a.z, b.z);
}

inline bool sameField(const Vec2& a, const Vec2& b) {
  return sameField(a.x, b.x) && sameField(a.y, b.y);
}

template <class T, size_t N>
bool sameField(const std::array<T, N>& a, const std::array<T, N>& b);
template <class T, size_t N>
bool sameField(const T (&a)[N], const T (&b)[N]);
template <class T>
bool sameField(const std::optional<T>& a, const std::optional<T>& b);
template <class T>
bool sameField(const std::vector<T>& a, const std::vector<T>& b);
template <class B>
bool sameField(const Flag<B>& a, const Flag<B>& b);
template <class V, class Check>
bool sameField(const Each<V, Check>& a, const Each<V, Check>& b);
template <CustomField T>
bool sameField(const T& a, const T& b);
template <DescribedStruct T>
bool sameField(const T& a, const T& b);

template <class T, size_t N>
bool sameField(const std::array<T, N>& a, const std::array<T, N>& b) {
  for (size_t i = 0; i < N; ++i) {
    if (!sameField(a[i], b[i])) return false;
  }
  return true;
}

template <class T, size_t N>
bool sameField(const T (&a)[N], const T (&b)[N]) {
  for (size_t i = 0; i < N; ++i) {
    if (!sameField(a[i], b[i])) return false;
  }
  return true;
}

template <class T>
bool sameField(const std::optional<T>& a, const std::optional<T>& b) {
  return a.has_value() == b.has_value() && (!a || sameField(*a, *b));
}

template <class T>
bool sameField(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return false;
  if constexpr (kMemoryIsWireForm<T>) {
    return a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
  } else {
    for (size_t i = 0; i < a.size(); ++i) {
      if (!sameField(a[i], b[i])) return false;
    }
    return true;
  }
}

template <class B>
bool sameField(const Flag<B>& a, const Flag<B>& b) {
  return a.value == b.value;
}

template <class V, class Check>
bool sameField(const Each<V, Check>& a, const Each<V, Check>& b) {
  return sameField(a.values, b.values);
}

// A field with a wire form of its own is what it sends: the same when its bytes are.
template <CustomField T>
bool sameField(const T& a, const T& b) {
  ByteWriter x, y;
  a.write(x);
  b.write(y);
  return x.bytes() == y.bytes();
}

template <DescribedStruct T>
bool sameField(const T& a, const T& b) {
  bool same = true;
  visitFields(a, [&](const auto&... x) {
    visitFields(b, [&](const auto&... y) { same = (sameField(x, y) && ...); });
  });
  return same;
}

// ---- the three uses ---------------------------------------------------------------------------

template <Described T>
void writeFields(ByteWriter& w, const T& value) {
  writeField(w, value);
}

// Reads every field, checks it and the struct; throws WireError. Leaves checking that nothing
// is left over to the caller.
template <Described T>
void readFields(ByteReader& r, T& value) {
  readField(r, value);
}

// Every field equal, floats by bit pattern.
template <Described T>
bool sameFields(const T& a, const T& b) {
  return sameField(a, b);
}

}  // namespace prism::wire

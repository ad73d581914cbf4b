// Example values of every message, made from the messages' field lists (wire/Fields.h) rather
// than written by hand per type: the default value, and a "filled" one with every field away from
// its default. The wire fuzzer's seeds (WireSeeds.cpp) and the tests of the generic codec
// (tests/common/wire/Messages_test.cpp) use them, so a new message type gets both for free.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "wire/FieldCodec.h"
#include "wire/Messages.h"

namespace prism::fuzz {

// Numbers 1 (floats 0.5), bools true, strings "x", enumerations their last enumerator, one
// element in every vector, optionals engaged: values that most checks accept.
template <wire::Number T>
void fill(T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    v = true;
  } else if constexpr (std::is_floating_point_v<T>) {
    v = T(0.5);
  } else {
    v = T(1);
  }
}

template <wire::Enumeration E>
void fill(E& v) {
  for (uint32_t raw = 0; raw < 64; ++raw) {
    using wire::isKnown;  // and, by argument-dependent lookup, prism::isKnown(Traversal)
    if (isKnown(static_cast<E>(raw))) v = static_cast<E>(raw);
  }
}

inline void fill(std::string& v) {
  v.assign(1,
           'x');  // not v = "x": GCC 12 warns of a memcpy overlap there (-Wrestrict, a false alarm)
}

inline void fill(Vec3& v) {
  v = Vec3(0.5f);
}

inline void fill(Vec2& v) {
  v = Vec2(0.5f);
}

template <class T, size_t N>
void fill(std::array<T, N>& values);
template <class T, size_t N>
void fill(T (&values)[N]);
template <class T>
void fill(std::optional<T>& value);
template <class T>
void fill(std::vector<T>& values);
template <class B>
void fill(wire::Flag<B> flag);
template <class V, class Check>
void fill(wire::Each<V, Check> checked);
template <wire::Described T>
void fill(T& value);

template <class T, size_t N>
void fill(std::array<T, N>& values) {
  for (T& v : values) fill(v);
}

template <class T, size_t N>
void fill(T (&values)[N]) {
  for (T& v : values) fill(v);
}

template <class T>
void fill(std::optional<T>& value) {
  fill(value.emplace());
}

template <class T>
void fill(std::vector<T>& values) {
  values.assign(1, T{});
  fill(values[0]);
}

template <class B>
void fill(wire::Flag<B> flag) {
  flag.value = true;
}

template <class V, class Check>
void fill(wire::Each<V, Check> checked) {
  fill(checked.values);
}

template <wire::Described T>
void fill(T& value) {
  wire::visitFields(value, [](auto&&... field) { (fill(field), ...); });
}

template <class T>
T filledExample() {
  T value{};
  fill(value);
  return value;
}

struct Example {
  const char* kind;            // "default" or "filled"
  std::vector<uint8_t> bytes;  // the full message
};

// The examples of T that its decoder accepts (the default value breaks some checks: an empty tile
// rectangle; the filled one others: a photon range past its budget, caustic settings out of
// range), each once.
template <class T>
std::vector<Example> acceptedExamples() {
  std::vector<Example> accepted;
  for (Example example : {Example{"default", wire::encode(T{})},
                          Example{"filled", wire::encode(filledExample<T>())}}) {
    try {
      wire::decode<T>(wire::decodeMessage(example.bytes));
    } catch (const wire::WireError&) {
      continue;
    }
    if (accepted.empty() || accepted.back().bytes != example.bytes) {
      accepted.push_back(std::move(example));
    }
  }
  return accepted;
}

}  // namespace prism::fuzz

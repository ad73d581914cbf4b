// A BVH leaf entry: which kind of primitive and its index in that kind's array, in 32 bits.
#pragma once

#include <cstdint>

namespace prism {

enum class PrimitiveKind : uint32_t { Triangle = 0, Sphere = 1, Cone = 2, Plane = 3 };

struct PrimitiveRef {
  static constexpr uint32_t kIndexBits = 30;
  static constexpr uint32_t kIndexMask = (1u << kIndexBits) - 1u;
  static constexpr uint32_t kMaxIndex = kIndexMask;

  static uint32_t make(PrimitiveKind kind, uint32_t index) {
    return (static_cast<uint32_t>(kind) << kIndexBits) | index;
  }
  static PrimitiveKind kind(uint32_t ref) { return static_cast<PrimitiveKind>(ref >> kIndexBits); }
  static uint32_t index(uint32_t ref) { return ref & kIndexMask; }
};

}  // namespace prism

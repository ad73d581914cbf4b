// A BVH leaf entry or a hit's primitive: which kind and its index in that kind's array, in 32
// bits. Triangles, by far the most numerous, take the top bit clear and 31 bits of index; every
// other kind (planes and the shapes of geometry/ShapeKinds.h) sets it, then names its kind in as
// many bits as the list needs, the rest being its index.
#pragma once

#include <bit>
#include <cstdint>

#include "geometry/ShapeKinds.h"

namespace prism {

#define PRISM_SHAPE_ENUMERATOR(Shape, plural) Shape,
enum class PrimitiveKind : uint32_t { Triangle, Plane, PRISM_SHAPE_KINDS(PRISM_SHAPE_ENUMERATOR) };
#undef PRISM_SHAPE_ENUMERATOR

// The kind of the k-th shape of geometry/ShapeKinds.h.
constexpr PrimitiveKind shapeKind(size_t k) {
  return static_cast<PrimitiveKind>(static_cast<uint32_t>(PrimitiveKind::Plane) + 1 + k);
}

// Whether the kind is a flat shape (Shape::kFlat): a pixel's footprint goes on unturned.
constexpr bool isFlatShape(PrimitiveKind kind) {
#define PRISM_SHAPE_FLAT(Shape, plural) \
  if (kind == PrimitiveKind::Shape) return Shape::kFlat;
  PRISM_SHAPE_KINDS(PRISM_SHAPE_FLAT)
#undef PRISM_SHAPE_FLAT
  return false;
}

struct PrimitiveRef {
  static constexpr uint32_t kOtherKinds = 1 + kShapeKindCount;  // planes and the shapes
  static constexpr uint32_t kOtherBit = 1u << 31;
  static constexpr uint32_t kKindBits = std::bit_width(kOtherKinds - 1);
  static constexpr uint32_t kIndexBits = 31 - kKindBits;
  static constexpr uint32_t kIndexMask = (1u << kIndexBits) - 1u;
  static constexpr uint32_t kMaxTriangleIndex = kOtherBit - 1u;
  static constexpr uint32_t kMaxIndex = kIndexMask;  // of a plane or a shape

  static constexpr uint32_t make(PrimitiveKind kind, uint32_t index) {
    if (kind == PrimitiveKind::Triangle) return index;
    return kOtherBit | ((static_cast<uint32_t>(kind) - 1u) << kIndexBits) | index;
  }
  static constexpr PrimitiveKind kind(uint32_t ref) {
    if (ref < kOtherBit) return PrimitiveKind::Triangle;
    return static_cast<PrimitiveKind>(1u + ((ref & ~kOtherBit) >> kIndexBits));
  }
  static constexpr uint32_t index(uint32_t ref) {
    return ref & (ref < kOtherBit ? kMaxTriangleIndex : kIndexMask);
  }
};

}  // namespace prism

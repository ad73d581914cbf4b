// A BVH leaf entry or a hit's primitive: which kind and its index in that kind's array, in 32
// bits. The kind takes as many top bits as the list of kinds needs (triangles, planes and the
// shapes of geometry/ShapeKinds.h), the index the rest. A uniform split keeps both a shift and a
// mask in the leaf loops (giving triangles 31 bits behind a branch cost 0.3-0.8 % more
// instructions a frame, tests/bench/frame_cost.sh).
#pragma once

#include <bit>
#include <cstdint>

#include "geometry/ShapeKinds.h"

namespace prism {

#define PRISM_SHAPE_ENUMERATOR(Shape, plural) Shape,
enum class PrimitiveKind : uint32_t { Triangle, Plane, PRISM_SHAPE_KINDS(PRISM_SHAPE_ENUMERATOR) };
#undef PRISM_SHAPE_ENUMERATOR
inline constexpr uint32_t kPrimitiveKindCount = 2 + kShapeKindCount;

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
  static constexpr uint32_t kKindBits = std::bit_width(kPrimitiveKindCount - 1u);
  static constexpr uint32_t kIndexBits = 32 - kKindBits;
  static constexpr uint32_t kIndexMask = (1u << kIndexBits) - 1u;
  static constexpr uint32_t kMaxIndex = kIndexMask;

  static constexpr uint32_t make(PrimitiveKind kind, uint32_t index) {
    return (static_cast<uint32_t>(kind) << kIndexBits) | index;
  }
  static constexpr PrimitiveKind kind(uint32_t ref) {
    return static_cast<PrimitiveKind>(ref >> kIndexBits);
  }
  static constexpr uint32_t index(uint32_t ref) { return ref & kIndexMask; }
};

// The most triangles a scene may hold: packed triangles are numbered pack · 4 + lane, and a pack
// may hold a single triangle.
inline constexpr uint64_t kMaxTriangles = (uint64_t{PrimitiveRef::kMaxIndex} + 1) / 4;

}  // namespace prism

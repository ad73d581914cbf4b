// How rays walk the scene's geometry. Every walk finds the same closest hits
// (tests/common/scene/Scene_test.cpp); the binary walk is the reference the fast one is
// measured and tested against.
#pragma once

namespace prism {

enum class Traversal {
  WideSimd,          // 8-wide BVH collapsed from the binary one, triangles tested 4 at a time
  WideScalarLeaves,  // the same wide BVH, triangles one at a time (measures what packs buy)
  BinaryScalar       // the binary SAH BVH, one box and one primitive at a time
};

}  // namespace prism

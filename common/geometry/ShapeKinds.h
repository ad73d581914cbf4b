// Every kind of bounded primitive besides the triangles of meshes, listed once. From this list
// follow the scene description's lists (scene/SceneDescription.h), their wire form, the YAML
// object kinds and their keys (parse/YamlSceneObjects.cpp), the BVH's kind tag
// (accel/PrimitiveRef.h), storage, leaf tests and surfaces (accel/SceneGeometry.h), the memory
// estimate (scene/GeometryMemory.cpp), the caustic casters (scene/Scene.cpp) and the summary's
// geometry line. docs/README.md, "Adding a primitive", says what a new kind provides.
//
// X(Shape, plural): the built primitive's type, whose description is Shape##Desc, and the name
// of the lists that hold them (SceneDescription::plural). The BVH numbers the kinds in this
// order, before the triangles.
//
// A kind's header defines
//   struct Shape:      bounds(), intersect(ray, tMax, t), surfacePoint(q, error, normal),
//                      materialId(), boundingBall(), kFlat (a pixel's footprint passes on
//                      unturned) and its field list (PRISM_WIRE_FIELDS);
//   struct ShapeDesc:  its fields with material, loc and caustic, kName (the scene file's key),
//                      keys() (geometry/ShapeKeys.h), problem() and shape();
// and, if the BVH should take it in parts, bvhParts(shape) and bvhPartCount(shape) beside it
// (as geometry/ConeSegments.h does for cones).
#pragma once

#include <cstddef>
#include <vector>

#include "geometry/Cone.h"
#include "geometry/ConeSegments.h"
#include "geometry/Disc.h"
#include "geometry/Sphere.h"

#define PRISM_SHAPE_KINDS(X) \
  X(Sphere, spheres)         \
  X(Cone, cones)             \
  X(Disc, discs)

// "plural," for each kind: the lists' names inside a field list.
#define PRISM_SHAPE_PLURAL_COMMA(Shape, plural) plural,

namespace prism {

#define PRISM_SHAPE_ONE(Shape, plural) +1
inline constexpr size_t kShapeKindCount = 0 PRISM_SHAPE_KINDS(PRISM_SHAPE_ONE);
#undef PRISM_SHAPE_ONE

// How many parts the BVH takes a shape in: one unless its header says otherwise.
template <class Shape>
size_t partCountForBvh(const Shape& shape) {
  if constexpr (requires { bvhPartCount(shape); }) {
    return static_cast<size_t>(bvhPartCount(shape));
  } else {
    return 1;
  }
}

}  // namespace prism

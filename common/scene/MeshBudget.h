// What geometry costs in memory, so meshes can be refused before they are read or built. The
// numbers are upper estimates of Prism's own structures on the rank that holds the most
// (a slave: the broadcast bytes, the decoded description and the built Scene at once);
// docs/reliability.md, "Limits", derives them and compares them with measured peaks.
#pragma once

#include <cstdint>

#include "util/MemorySize.h"

namespace prism {

// Per triangle, at the peak (the binary BVH build): indices in the wire bytes and the
// description (12 + 12), the Scene's gathered Triangle (44; only for the walks without packs,
// whose packs are filled from the description), the builder's SIMD copy of its box and the BVH
// order (32 + 4; the builder asks for each box, no other array of them exists), up to two
// 32-byte BVH nodes (64), the parallel build's second node array (at most 32) and its shading
// indices (12): 212. While the triangles are reordered into BVH order the builder's copy and the
// second node array are gone and the Triangle exists twice (196); the wide BVH and its triangle
// packs (about 65) come after the gathered copies are freed and the binary tree is dropped
// (SceneGeometry.cpp), so neither raises the peak.
inline constexpr uint64_t kBytesPerTriangle = 212;
// Per vertex: position and normal in the wire bytes and the description (24 + 24), the
// Scene's shading normal (12), rounded up.
inline constexpr uint64_t kBytesPerVertex = 64;
// A plane or a shape's BVH part (geometry/ShapeKinds.h; a slanted cone enters in parts), at the
// peak (the collapse into the wide BVH): its wire bytes and description (about 60), the
// builder's box and the BVH order (36), up to two 32-byte binary nodes and the parallel build's
// copy of them (96), its share of the wide nodes (about 80: shapes get leaves of their own, one
// test each), the Scene's copy (20 for a sphere, 36 for a disc, 80 for a cone part) and leaf
// entry, with room for 2 MiB pages rounding up. Measured (docs/reliability.md): 323–354 per
// sphere, 312 per cone part.
inline constexpr uint64_t kBytesPerOtherPrimitive = 448;

inline uint64_t meshBuildBytes(uint64_t triangles, uint64_t vertices) {
  return saturatingAdd(saturatingMultiply(triangles, kBytesPerTriangle),
                       saturatingMultiply(vertices, kBytesPerVertex));
}

// Reading an OBJ file (parse/ObjLoader.cpp), its text included: the parsed positions (12 per
// 'v'), normals (12 per 'vn') and texture coordinates (8 per 'vt'), each face corner's position
// index (4, and 4 more each for its normal and texture coordinate indices when the file has
// them), a byte per face and, when the file has 'usemtl', 4 for its material; then numbering the
// output vertices (8 per position: its first number and source, 8 more with normals and 8 more
// with texture coordinates), the output positions, normals (12 each per position) and texture
// coordinates (8), the triangle indices (12 per triangle) and materials (4, with 'usemtl'). A
// sum: the text and the corner arrays are gone before some of the later arrays exist, so this is
// an upper bound.
inline uint64_t objReadBytes(uint64_t textBytes, uint64_t positions, uint64_t normals, uint64_t uvs,
                             uint64_t corners, uint64_t faces, uint64_t triangles,
                             bool faceMaterials) {
  const bool withNormals = normals > 0;
  const bool withUvs = uvs > 0;
  uint64_t perPosition = 12 + 8 + 12;
  if (withNormals) perPosition += 8 + 12;
  if (withUvs) perPosition += 8 + 8;
  uint64_t bytes = textBytes;
  bytes = saturatingAdd(bytes, saturatingMultiply(positions, perPosition));
  bytes = saturatingAdd(bytes, saturatingMultiply(normals, 12));
  bytes = saturatingAdd(bytes, saturatingMultiply(uvs, 8));
  bytes = saturatingAdd(bytes,
                        saturatingMultiply(corners, 4 + (withNormals ? 4 : 0) + (withUvs ? 4 : 0)));
  bytes = saturatingAdd(bytes, saturatingMultiply(faces, faceMaterials ? 5 : 1));
  return saturatingAdd(bytes, saturatingMultiply(triangles, faceMaterials ? 16 : 12));
}

// Reading a PLY file (parse/PlyLoader.cpp), its bytes included: positions and normals (12 each
// per vertex), texture coordinates (8) and colours (12), and the triangle indices (12 per
// triangle), made directly from the body.
inline uint64_t plyReadBytes(uint64_t fileBytes, uint64_t vertices, bool normals, bool uvs,
                             bool colors, uint64_t triangles) {
  const uint64_t perVertex = 12 + (normals ? 12 : 0) + (uvs ? 8 : 0) + (colors ? 12 : 0);
  uint64_t bytes = fileBytes;
  bytes = saturatingAdd(bytes, saturatingMultiply(vertices, perVertex));
  return saturatingAdd(bytes, saturatingMultiply(triangles, 12));
}

// Reading a scene file of this size may take, besides the text itself: NFF builds at most one
// triangle (3 positions, 3 normals, 3 indices: 84 bytes) per 6-byte vertex line, so 14 bytes
// per byte (measured: a 10.7 MB file of 400 000 triangles peaked 93 MB above an empty scene,
// parse and build together); yaml-cpp's node tree takes about 110 bytes per byte of dense YAML
// (measured: 552 MB for a 5.0 MB file of 60 000 one-line triangles), so 128 is the bound.
inline constexpr uint64_t kNffParseBytesPerFileByte = 1 + 14;
inline constexpr uint64_t kYamlParseBytesPerFileByte = 1 + 128;

}  // namespace prism

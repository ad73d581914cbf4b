// PLY triangle meshes referenced from a scene: ASCII and binary (little and big endian) bodies,
// vertex positions (x, y, z), normals (nx, ny, nz), texture coordinates (u, v; or s, t;
// texture_u, texture_v; texture_s, texture_t) and colours (red, green, blue: integers are
// sRGB-encoded fractions of their type's largest value, made linear; floats are linear), each
// kept when all its properties are there; faces as lists of vertex indices ("vertex_indices" or
// "vertex_index"), polygons split into fans. Other elements and properties (alpha, edges, ...)
// are read past.
#pragma once

#include <string>
#include <string_view>

#include "scene/SceneDescription.h"
#include "util/MemorySize.h"

namespace prism {

// Loads the PLY file at path into one mesh; its vertices are the file's, in its order. Normals
// are kept when every vertex has a non-zero one. Errors name the file and where in it: line and
// column in a header or an ASCII body, the element and byte offset in a binary body. A file
// larger than the memory limit is refused before it is read, a mesh whose reading and building
// would pass it (scene/MeshBudget.h) before its arrays are allocated, and element counts the
// file cannot hold before anything is. referencedFrom is where the scene names the file.
// Throws SceneError.
MeshDesc loadPlyMesh(const std::string& path, const FileLoc& referencedFrom,
                     const MemoryLimit& limit = {});

// The same from the file's bytes in memory (the fuzzer feeds it this way).
MeshDesc parsePlyMesh(std::string_view bytes, const std::string& path,
                      const FileLoc& referencedFrom, const MemoryLimit& limit = {});

}  // namespace prism

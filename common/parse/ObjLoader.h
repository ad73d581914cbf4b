// Wavefront OBJ triangle meshes referenced from a scene.
#pragma once

#include <string>

#include "scene/SceneDescription.h"
#include "util/MemorySize.h"

namespace prism {

// Loads the OBJ file at path into a single world-space mesh (faces triangulated, vertex normals
// kept when every face has them). referencedFrom is where the scene names the file; errors point
// there when the file is missing and into the OBJ file otherwise. Throws SceneError.
// A mesh whose reading and building (scene/MeshBudget.h) would pass the memory limit is refused
// before its geometry is allocated: the file size is checked before it is read, the counts of
// its 'v', 'vn' and 'f' lines before tinyobjloader reads it.
MeshDesc loadObjMesh(const std::string& path, const FileLoc& referencedFrom,
                     const MemoryLimit& limit = {});

// The same from OBJ text already in memory (the fuzzer feeds it this way); path names the text in
// errors and becomes the mesh's source.
MeshDesc parseObjMesh(const std::string& text, const std::string& path,
                      const FileLoc& referencedFrom, const MemoryLimit& limit = {});

}  // namespace prism

// Wavefront OBJ triangle meshes referenced from a scene.
#pragma once

#include <string>
#include <string_view>

#include "scene/SceneDescription.h"
#include "util/MemorySize.h"

namespace prism {

// Loads the OBJ file at path into a single world-space mesh (faces triangulated, vertex normals
// kept when every face has them), on all the cores this process may use; the mesh is the same
// whatever their number. referencedFrom is where the scene names the file; errors point there
// when the file is missing and into the OBJ file (file:line:col) otherwise. Throws SceneError.
// A mesh whose reading and building (scene/MeshBudget.h) would pass the memory limit is refused
// before its geometry is allocated: the file size is checked before it is read, the counts of
// its 'v', 'vn' and 'f' lines before a number is parsed.
MeshDesc loadObjMesh(const std::string& path, const FileLoc& referencedFrom,
                     const MemoryLimit& limit = {});

// The same from OBJ text already in memory (the fuzzer feeds it this way); path names the text in
// errors and becomes the mesh's source. pieceBytes sets how finely the text is cut for the
// threads (0: the loader's choice); tests cut it finely to show that the cut changes nothing.
MeshDesc parseObjMesh(std::string_view text, const std::string& path, const FileLoc& referencedFrom,
                      const MemoryLimit& limit = {}, size_t pieceBytes = 0);

}  // namespace prism

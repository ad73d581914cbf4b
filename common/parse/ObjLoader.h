// Wavefront OBJ models: the triangle mesh, with the materials of its MTL libraries and their
// textures.
#pragma once

#include <string>
#include <string_view>

#include "parse/CompanionFiles.h"
#include "scene/ModelDesc.h"
#include "util/MemorySize.h"

namespace prism {

// Loads the OBJ file at path into a model of one world-space mesh (faces triangulated, vertex
// normals kept when every face has them, texture coordinates when a face names them), on all
// the cores this process may use; the model is the same whatever their number. Its 'mtllib'
// libraries are read through files (relative to the OBJ's folder) and each face takes the
// material of the last 'usemtl' before it (docs/scene-format.md, "OBJ"). The model holds the
// materials faces use, with their textures; a file without 'usemtl' brings none, and its mesh
// is exactly what the geometry alone gives. referencedFrom is where the scene names the file;
// errors point there when the file is missing and into the OBJ or MTL file (file:line:col)
// otherwise. Throws SceneError; what is skipped or missing (a library, a texture, a statement
// Prism does not model) is a warning in the model. A mesh whose reading and building
// (scene/MeshBudget.h) would pass the memory limit is refused before its geometry is allocated:
// the file size is checked before it is read, the counts of its 'v', 'vn', 'vt' and 'f' lines
// before a number is parsed.
ModelDesc loadObjModel(const std::string& path, const FileLoc& referencedFrom,
                       const MemoryLimit& limit = {}, const CompanionFiles& files = filesOnDisk());

// The same from OBJ text already in memory (the fuzzer feeds it this way); path names the text in
// errors, is the folder its libraries are looked for in, and becomes the mesh's source.
// pieceBytes sets how finely the text is cut for the threads (0: the loader's choice); tests cut
// it finely to show that the cut changes nothing.
ModelDesc parseObjModel(std::string_view text, const std::string& path,
                        const FileLoc& referencedFrom, const MemoryLimit& limit = {},
                        size_t pieceBytes = 0, const CompanionFiles& files = filesOnDisk());

}  // namespace prism

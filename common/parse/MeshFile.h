// The mesh files a scene may name, read by the loader their name calls for.
#pragma once

#include <string>

#include "scene/SceneDescription.h"
#include "util/MemorySize.h"

namespace prism {

// A ".ply" file (any case) through loadPlyMesh, anything else through loadObjMesh; the
// arguments and errors are theirs.
MeshDesc loadMeshFile(const std::string& path, const FileLoc& referencedFrom,
                      const MemoryLimit& limit = {});

}  // namespace prism

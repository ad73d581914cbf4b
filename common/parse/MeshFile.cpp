#include "parse/MeshFile.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "parse/ObjLoader.h"
#include "parse/PlyLoader.h"

namespace prism {

MeshDesc loadMeshFile(const std::string& path, const FileLoc& referencedFrom,
                      const MemoryLimit& limit) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".ply") return loadPlyMesh(path, referencedFrom, limit);
  return loadObjMesh(path, referencedFrom, limit);
}

}  // namespace prism

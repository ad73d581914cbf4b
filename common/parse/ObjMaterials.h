// The materials an OBJ file brings: the MTL libraries its 'mtllib' lines name (parse/MtlParser.h),
// their materials numbered in the order defined, so that the pieces of the OBJ read in parallel
// (parse/ObjChunk.h) can give each face its material's number, and then the materials the faces
// use, with their textures, made into the model's.
#pragma once

#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "parse/CompanionFiles.h"
#include "parse/MtlParser.h"
#include "parse/ObjChunk.h"
#include "scene/ModelDesc.h"

namespace prism {

class ObjMaterials {
 public:
  // objPath: the OBJ file, whose folder 'mtllib' names are relative to. Warnings (a library or
  // texture not found, a material defined twice, what the MTL files hold that Prism does not
  // model) are added to `warnings`.
  ObjMaterials(const std::string& objPath, const CompanionFiles& files,
               std::vector<std::string>& warnings);

  // Reads the libraries one 'mtllib' line names (its rest of line, at line:column of the OBJ):
  // the whole rest as one file where that file exists (a name with blanks), otherwise each word.
  // A library named again is not read again. Throws SceneError for a malformed MTL file.
  void readLibraries(std::string_view names, uint64_t line, int column);

  // Every name the libraries define, for the faces.
  const ObjMaterialNames& names() const { return names_; }

  // Whether some 'mtllib' line named a library that was read.
  bool anyLibraryRead() const { return !read_.empty(); }

  // Adds the materials faces use to model (in the order the libraries define them, then the
  // default material where faces use it) with the textures their map_Kd names, each file once.
  // used[n]: whether a face uses material number n. Returns each number's index in
  // model.materials (kDefaultFaceMaterial at index names().size()). A texture file that is
  // missing is a warning; one that is not an image, or too large for limit, a SceneError.
  std::vector<MaterialId> addUsed(const std::vector<bool>& used, bool defaultUsed, ModelDesc& model,
                                  const MemoryLimit& limit) const;

 private:
  void readLibrary(const std::string& file, uint64_t line, int column);
  void warnMissing(std::string_view name, const std::string& lookedFor, uint64_t line);
  // Whether the library of this name was warned about before (and notes it).
  bool warnedOnce(const std::string& library);

  std::string objPath_;
  std::string folder_;
  const CompanionFiles& files_;
  std::vector<std::string>& warnings_;
  ObjMaterialNames names_;
  std::vector<MtlMaterial> materials_;  // by number
  std::vector<std::string> read_;       // the libraries read
  std::vector<std::string> redefined_;  // names defined again, each warned once
  std::set<std::string> missing_;       // libraries warned about, each once
};

}  // namespace prism

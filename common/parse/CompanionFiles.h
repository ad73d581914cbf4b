// The files a model file names beside itself (an OBJ's .mtl libraries and the textures they
// name), reached through one small interface so that tests and the fuzzers can hand a loader
// files held in memory instead of the disk.
#pragma once

#include <string>
#include <string_view>

#include "scene/SceneDescription.h"
#include "util/MemorySize.h"

namespace prism {

class CompanionFiles {
 public:
  virtual ~CompanionFiles() = default;

  // Whether path names a regular file that can be opened.
  virtual bool isFile(const std::string& path) const = 0;
  // The whole file as text. Throws SceneError at `at` naming the file when it cannot be read.
  virtual std::string readText(const std::string& path, const FileLoc& at) const = 0;
  // The image at path (parse/TextureFile.h's loadTextureFile). Throws SceneError at `at`.
  virtual TextureDesc readTexture(const std::string& path, const FileLoc& at,
                                  const MemoryLimit& limit) const = 0;
};

// The files on disk, through readTextFile and loadTextureFile.
const CompanionFiles& filesOnDisk();

// Where a file a model names is found.
struct CompanionFile {
  std::string found;      // the file, or empty where it was not found
  std::string lookedFor;  // where it was first looked for (for the warning when it is missing)
};

// Finds the file a model file or an MTL library names (name as written: '\' separators are
// read as '/'), relative to folder unless it is absolute; where it is not there, its last part
// in folder (files exported with the absolute paths of the machine that wrote them).
CompanionFile findCompanionFile(std::string_view name, const std::string& folder,
                                const CompanionFiles& files);

}  // namespace prism

#include "parse/CompanionFiles.h"

#include <algorithm>
#include <filesystem>

#include "parse/SceneLoader.h"
#include "parse/TextureFile.h"

namespace prism {

namespace {

class DiskFiles final : public CompanionFiles {
 public:
  bool isFile(const std::string& path) const override {
    std::error_code error;
    return std::filesystem::is_regular_file(path, error);
  }
  std::string readText(const std::string& path, const FileLoc& at) const override {
    return readTextFile(path, at);
  }
  TextureDesc readTexture(const std::string& path, const FileLoc& at,
                          const MemoryLimit& limit) const override {
    return loadTextureFile(path, at, limit);
  }
};

}  // namespace

CompanionFile findCompanionFile(std::string_view name, const std::string& folder,
                                const CompanionFiles& files) {
  std::string written(name);
  std::replace(written.begin(), written.end(), '\\', '/');
  const std::filesystem::path asWritten(written);
  const std::filesystem::path base(folder);
  CompanionFile file;
  file.lookedFor =
      (asWritten.is_absolute() ? asWritten : base / asWritten).lexically_normal().string();
  if (files.isFile(file.lookedFor)) {
    file.found = file.lookedFor;
    return file;
  }
  const std::filesystem::path lastPart = asWritten.filename();
  if (!lastPart.empty() && lastPart != asWritten) {
    const std::string beside = (base / lastPart).lexically_normal().string();
    if (files.isFile(beside)) file.found = beside;
  }
  return file;
}

const CompanionFiles& filesOnDisk() {
  static const DiskFiles files;
  return files;
}

}  // namespace prism

// Chooses a scene parser by file extension and reads scene files as text.
#include "parse/SceneLoader.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "parse/ModelFile.h"
#include "parse/ModelScene.h"
#include "parse/NffParser.h"
#include "parse/YamlSceneParser.h"
#include "scene/MeshBudget.h"

namespace prism {

namespace {

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Errors about the file itself point at whoever named it, or at the file when nobody did.
[[noreturn]] void failToRead(const std::string& path, const FileLoc& referencedFrom,
                             const std::string& why) {
  if (referencedFrom.file.empty()) throw SceneError(FileLoc{path}, "cannot read file: " + why);
  throw SceneError(referencedFrom, "cannot read '" + path + "': " + why);
}

}  // namespace

std::string readTextFile(const std::string& path, const FileLoc& referencedFrom) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                             &std::fclose);
  if (!file) failToRead(path, referencedFrom, std::strerror(errno));
  // fopen succeeds on a directory on Linux; say what it is rather than report a read error.
  struct stat info {};
  if (fstat(fileno(file.get()), &info) == 0 && S_ISDIR(info.st_mode)) {
    failToRead(path, referencedFrom, "it is a directory");
  }
  std::string text;
  // Sized once: appending chunk by chunk re-copied a 1.5 MB NFF file (teapot-s12) a dozen times.
  if (info.st_size > 0) text.reserve(static_cast<size_t>(info.st_size));
  char buffer[1 << 16];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) text.append(buffer, n);
  if (std::ferror(file.get())) failToRead(path, referencedFrom, std::strerror(errno));
  return text;
}

SceneDescription loadScene(const std::string& path, const MemoryLimit& limit) {
  const std::string extension = lowercase(std::filesystem::path(path).extension().string());
  const auto checkReadFits = [&](uint64_t bytesPerFileByte, const char* parser) {
    std::error_code error;
    const uintmax_t size = std::filesystem::file_size(path, error);
    const uint64_t needed = saturatingMultiply(error ? 0 : size, bytesPerFileByte);
    if (needed > limit.bytes) {
      throw SceneError(FileLoc{path},
                       memoryRefusal(std::string("reading this ") + std::to_string(size) +
                                         "-byte " + parser + " file",
                                     needed, limit, "split or simplify the scene"));
    }
  };
  if (extension == ".yaml" || extension == ".yml") {
    checkReadFits(kYamlParseBytesPerFileByte, "YAML");
    return parseYamlScene(readTextFile(path), path, limit);
  }
  if (extension == ".nff") {
    checkReadFits(kNffParseBytesPerFileByte, "NFF");
    return parseNff(readTextFile(path), path);
  }
  if (extension == ".obj" || extension == ".ply" || extension == ".gltf" || extension == ".glb") {
    return sceneOfModel(loadModelFile(path, FileLoc{}, limit));
  }
  constexpr const char* kExpected =
      "(expected .yaml, .yml, .nff, or a model: .obj, .ply, .gltf, .glb)";
  if (extension.empty()) {
    throw SceneError(FileLoc{path}, std::string("scene file has no extension ") + kExpected);
  }
  throw SceneError(FileLoc{path}, "unsupported scene format '" + extension + "' " + kExpected);
}

}  // namespace prism

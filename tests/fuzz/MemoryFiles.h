// Files held in memory for the model loaders (parse/CompanionFiles.h): tests and the fuzz
// harnesses hand an OBJ its MTL libraries and textures without touching the disk.
#pragma once

#include <filesystem>
#include <map>
#include <span>
#include <string>

#include "parse/CompanionFiles.h"
#include "parse/TextureFile.h"

namespace prism {

class MemoryFiles final : public CompanionFiles {
 public:
  // A file of these bytes at path (a texture's bytes are decoded as PNG or JPEG).
  MemoryFiles& add(const std::string& path, std::string bytes) {
    files_[key(path)] = std::move(bytes);
    return *this;
  }
  // A texture file whose pixels are already decoded.
  MemoryFiles& addTexture(const std::string& path, TextureDesc texture) {
    texture.path = key(path);
    textures_[key(path)] = std::move(texture);
    return *this;
  }

  bool isFile(const std::string& path) const override {
    return files_.count(key(path)) > 0 || textures_.count(key(path)) > 0;
  }
  std::string readText(const std::string& path, const FileLoc& at) const override {
    ++reads_[key(path)];
    const auto it = files_.find(key(path));
    if (it == files_.end()) throw SceneError(at, "cannot read '" + path + "'");
    return it->second;
  }
  TextureDesc readTexture(const std::string& path, const FileLoc& at,
                          const MemoryLimit& limit) const override {
    ++reads_[key(path)];
    if (const auto it = textures_.find(key(path)); it != textures_.end()) return it->second;
    const auto it = files_.find(key(path));
    if (it == files_.end()) throw SceneError(at, "texture '" + path + "': cannot read it");
    const std::span<const uint8_t> bytes(reinterpret_cast<const uint8_t*>(it->second.data()),
                                         it->second.size());
    return decodeTexture(bytes, key(path), at, limit);
  }

  // How many times the file at path was read.
  int reads(const std::string& path) const {
    const auto it = reads_.find(key(path));
    return it == reads_.end() ? 0 : it->second;
  }

 private:
  static std::string key(const std::string& path) {
    return std::filesystem::path(path).lexically_normal().string();
  }

  std::map<std::string, std::string> files_;
  std::map<std::string, TextureDesc> textures_;
  mutable std::map<std::string, int> reads_;
};

}  // namespace prism

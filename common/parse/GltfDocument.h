// What the parts of the glTF loader share while one file is read: its JSON, the top-level
// arrays by index, the bytes of its buffers, the memory limit and the warnings so far.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "parse/GltfJson.h"
#include "parse/GltfLoader.h"
#include "util/MemorySize.h"

namespace prism {

struct GltfDocument {
  GltfDocument(std::string file_, GltfJson root_)
      : file(std::move(file_)), root(std::move(root_)) {}

  std::string file;  // for messages and texture names
  GltfJson root;
  std::vector<GltfJson> accessors, bufferViews, buffers, meshes, nodes, materials, textures, images,
      cameras, lights;
  std::vector<std::span<const uint8_t>> bufferBytes;           // per buffer, byteLength long
  std::vector<std::unique_ptr<std::vector<uint8_t>>> decoded;  // data: URI buffers, owned
  GltfFileReader readFile;
  MemoryLimit limit;
  FileLoc referencedFrom;       // where a scene names the file: memory refusals are reported there
  uint64_t committedBytes = 0;  // what the limit is already charged with (JSON, decoded buffers)
  std::set<std::string> warnedKinds;
  std::vector<std::string> warnings;

  // Adds "file: message" unless a warning of this kind was given already.
  void warn(const std::string& kind, const std::string& message) {
    if (warnedKinds.insert(kind).second) warnings.push_back(file + ": " + message);
  }
  // The object at index i of a top-level array, or an error at `from` naming the index.
  const GltfJson& at(const std::vector<GltfJson>& list, uint64_t i, const GltfJson& from,
                     std::string_view listName) const {
    if (i >= list.size()) {
      from.fail("refers to " + std::string(listName) + "[" + std::to_string(i) +
                "], but the file has " + std::to_string(list.size()));
    }
    return list[i];
  }
  // Charges bytes against the limit; throws SceneError (what, refused before allocation).
  void charge(uint64_t bytes, const std::string& what);
};

}  // namespace prism

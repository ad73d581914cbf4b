// The binary glTF container (.glb): a 12-byte header ("glTF", version 2, total length), a JSON
// chunk and an optional BIN chunk. The chunks are views into the file's bytes: nothing is copied.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace prism {

struct GlbChunks {
  std::string_view json;
  std::span<const uint8_t> bin;  // empty when the file has no BIN chunk
  bool hasBin = false;
};

// Whether bytes start with the GLB magic "glTF".
bool looksLikeGlb(std::string_view bytes);

// Splits a .glb file. Throws SceneError "file: byte N: what is wrong" for a bad magic or
// version, a length that disagrees with the file, and chunks that are truncated, misordered or
// of the wrong type.
GlbChunks splitGlb(std::string_view bytes, const std::string& file);

}  // namespace prism

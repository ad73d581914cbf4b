#include "fuzz/Harnesses.h"
#include "fuzz/SceneInvariants.h"
#include "parse/PlyLoader.h"

namespace prism::fuzz {

Outcome fuzzPly(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  return meshOutcome([&] {
    return parsePlyMesh(bytes, "fuzz-input.ply", FileLoc{"fuzz-input.yaml", 1, 1});
  });
}

}  // namespace prism::fuzz

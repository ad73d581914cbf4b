#include "fuzz/Harnesses.h"
#include "fuzz/SceneInvariants.h"
#include "parse/ObjLoader.h"

namespace prism::fuzz {

Outcome fuzzObj(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  return meshOutcome([&] {
    return parseObjMesh(text, "fuzz-input.obj", FileLoc{"fuzz-input.yaml", 1, 1});
  });
}

}  // namespace prism::fuzz

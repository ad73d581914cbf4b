#include "fuzz/Harnesses.h"
#include "fuzz/ModelFiles.h"
#include "fuzz/SceneInvariants.h"
#include "parse/ObjLoader.h"

namespace prism::fuzz {

Outcome fuzzObj(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  static const MemoryFiles files = harnessFiles();
  return modelOutcome([&] {
    return parseObjModel(text, "fuzz-input.obj", FileLoc{"fuzz-input.yaml", 1, 1}, {}, 0, files);
  });
}

}  // namespace prism::fuzz

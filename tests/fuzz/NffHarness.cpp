#include "fuzz/Harnesses.h"
#include "fuzz/SceneInvariants.h"
#include "parse/NffParser.h"

namespace prism::fuzz {

Outcome fuzzNff(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  SceneDescription scene;
  try {
    scene = parseNff(text, "fuzz-input.nff");
  } catch (const SceneError&) {
    return Outcome::Rejected;
  }
  checkScene(scene);
  return Outcome::Accepted;
}

}  // namespace prism::fuzz

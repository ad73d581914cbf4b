#include "fuzz/Harnesses.h"
#include "fuzz/SceneInvariants.h"
#include "parse/YamlSceneParser.h"

namespace prism::fuzz {

Outcome fuzzYamlScene(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  SceneDescription scene;
  try {
    scene = parseYamlScene(text, PRISM_SOURCE_DIR "/scenes/fuzz-input.yaml");
  } catch (const SceneError&) {
    return Outcome::Rejected;
  }
  checkScene(scene);
  return Outcome::Accepted;
}

}  // namespace prism::fuzz

// Writes the wire fuzzer's seeds into tests/fuzz/corpus/wire: for every message type, the
// examples that WireExamples.h makes from its field list (its default value, and one with every
// field set) as full messages (for the envelope checks) and as the same payload behind a type
// byte (the harness's second form), so the fuzzer starts inside every payload decoder; scenes
// from the example scene files and the geometries built from them; and two refused messages.
// (the long runs then merged more inputs into that folder, and the seeds of earlier versions,
// written by hand, stay there):
//   build/tests/fuzz/prism_fuzz_wire_seeds tests/fuzz/corpus/wire
//       scenes/caustic-{glass-sphere,ring}.yaml scenes/caustic-map-*.yaml scenes/lambert-plane.yaml
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "fuzz/WireExamples.h"
#include "parse/SceneLoader.h"
#include "scene/Scene.h"
#include "wire/GeometryCodec.h"
#include "wire/Messages.h"

namespace {

using namespace prism;
using namespace prism::wire;

void writeFile(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

void writeSeed(const std::string& dir, const std::string& name, const std::vector<uint8_t>& bytes) {
  writeFile(dir + "/" + name + ".msg", bytes);
  // The payload behind its type byte.
  const Message message = decodeMessage(bytes);
  std::vector<uint8_t> typed = {static_cast<uint8_t>(message.type)};
  typed.insert(typed.end(), message.payload.begin(), message.payload.end());
  writeFile(dir + "/" + name + ".typed", typed);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR [SCENE...]\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  for (int i = 2; i < argc; ++i) {
    const std::string path = argv[i];
    const std::string stem = path.substr(path.find_last_of('/') + 1);
    const SceneDescription scene = loadScene(path);
    writeSeed(dir, "scene-" + stem.substr(0, stem.find('.')), encodeScene(scene));
    // The geometry rank 0 builds from it, as its geometry broadcast carries it.
    writeSeed(dir, "geometry-" + stem.substr(0, stem.find('.')), encode(Scene(scene).geometry()));
  }
  forEachMessageType([&](auto type) {
    using T = typename decltype(type)::type;
    const std::string name = messageTypeName(MessageTraits<T>::kType);
    for (const fuzz::Example& example : fuzz::acceptedExamples<T>()) {
      writeSeed(dir, name + "-" + example.kind, example.bytes);
    }
  });
  // Refused ones: a truncated message and a flipped payload byte.
  std::vector<uint8_t> bytes = encode(ReadyMessage{0.25, 8});
  bytes.pop_back();
  writeFile(dir + "/bad-truncated.msg", bytes);
  bytes = encode(ErrorMessage{"flipped"});
  bytes.back() ^= 1;
  writeFile(dir + "/bad-checksum.msg", bytes);
  return 0;
}

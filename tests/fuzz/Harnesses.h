// The fuzz harnesses: one function per input format, shared by the libFuzzer entry point
// (FuzzerMain.cpp, clang builds with PRISM_FUZZ) and the corpus replay in the normal test suite
// (FuzzReplay_test.cpp). Each feeds arbitrary bytes to a parser or decoder, treats that
// component's own error type as a clean rejection, and checks what it accepts against the
// invariants later stages rely on. Anything else (a crash, a sanitizer report, another exception,
// a hang) is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace prism::fuzz {

enum class Outcome { Accepted, Rejected };

// Thrown when accepted input breaks an invariant: a finding, like a crash.
class InvariantBroken : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

// YAML scene text, parsed as if it were scenes/fuzz-input.yaml, so that relative mesh and image
// paths reach the example assets.
Outcome fuzzYamlScene(const uint8_t* data, size_t size);
// NFF scene text.
Outcome fuzzNff(const uint8_t* data, size_t size);
// OBJ model text, with two material libraries and a texture beside it (ModelFiles.h).
Outcome fuzzObj(const uint8_t* data, size_t size);
// MTL library text, as the library of a small OBJ whose faces name common material names.
Outcome fuzzMtl(const uint8_t* data, size_t size);
// PLY mesh files (header and ASCII or binary body).
Outcome fuzzPly(const uint8_t* data, size_t size);
// glTF models: the bytes as a .gltf (JSON; external files are missing) and as a .glb.
Outcome fuzzGltf(const uint8_t* data, size_t size);
Outcome fuzzGlb(const uint8_t* data, size_t size);
// Wire messages: the bytes as an envelope, and the bytes after the first as the payload of a
// valid envelope whose type the first byte chooses (the checksum would otherwise stop nearly
// every mutation before the payload decoders).
Outcome fuzzWire(const uint8_t* data, size_t size);
// Viewer protocol messages (master/remote/ViewProtocol.h): the bytes as a whole message, and the
// bytes after the first as the fields of a message whose type the first byte chooses.
Outcome fuzzView(const uint8_t* data, size_t size);

struct Harness {
  const char* name;  // the folder under tests/fuzz/corpus/ and tests/fuzz/regressions/
  Outcome (*run)(const uint8_t* data, size_t size);
};

inline const std::vector<Harness>& harnesses() {
  static const std::vector<Harness> all = {{"yaml_scene", fuzzYamlScene},
                                           {"nff", fuzzNff},
                                           {"obj", fuzzObj},
                                           {"mtl", fuzzMtl},
                                           {"ply", fuzzPly},
                                           {"gltf", fuzzGltf},
                                           {"glb", fuzzGlb},
                                           {"wire", fuzzWire},
                                           {"view", fuzzView}};
  return all;
}

}  // namespace prism::fuzz

#include "fuzz/Harnesses.h"
#include "fuzz/ModelFiles.h"
#include "fuzz/SceneInvariants.h"
#include "parse/ObjLoader.h"

namespace prism::fuzz {

namespace {

// A square whose faces name the materials an MTL file most often defines, and the harness's.
constexpr const char* kObj =
    "mtllib fuzz-input.mtl fuzz.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "usemtl Material\nf 1/1 2/2 3/3\n"
    "usemtl a\nf 1/1 3/3 4/4\n"
    "usemtl material_0\nf 1/1 2/2 4/4\n"
    "usemtl default\nf 2/2 3/3 4/4\n"
    "usemtl glass\nf 4/4 3/3 2/2\n"
    "usemtl b\nf 3/3 2/2 1/1\n";

}  // namespace

Outcome fuzzMtl(const uint8_t* data, size_t size) {
  const MemoryFiles files =
      harnessFiles("fuzz-input.mtl", std::string(reinterpret_cast<const char*>(data), size));
  return modelOutcome([&] {
    return parseObjModel(kObj, "fuzz-input.obj", FileLoc{"fuzz-input.yaml", 1, 1}, {}, 0, files);
  });
}

}  // namespace prism::fuzz

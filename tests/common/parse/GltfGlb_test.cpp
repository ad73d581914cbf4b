#include "parse/GltfGlb.h"

#include <gtest/gtest.h>

#include "common/parse/GltfAssets.h"

namespace prism {
namespace {

std::string errorOf(const std::string& bytes) {
  try {
    splitGlb(bytes, "m.glb");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(GltfGlb, ChunksAreViewsIntoTheFile) {
  gltftest::GltfAssets a;
  a.view(std::string("abcd"));
  const std::string glb = a.glb("");
  const GlbChunks chunks = splitGlb(glb, "m.glb");
  EXPECT_TRUE(chunks.json.starts_with("{\"asset\""));
  ASSERT_TRUE(chunks.hasBin);
  EXPECT_EQ(chunks.bin.size(), 4u);
  EXPECT_EQ(reinterpret_cast<const char*>(chunks.bin.data()), glb.data() + glb.size() - 4);
}

TEST(GltfGlb, BadContainersAreRefusedWithTheirByte) {
  gltftest::GltfAssets a;
  a.view(std::string("abcdefgh"));
  const std::string glb = a.glb("");
  EXPECT_EQ(errorOf("glT"), "m.glb: byte 0: too short for a binary glTF header (12 bytes)");
  EXPECT_EQ(errorOf("xxxx" + glb.substr(4)),
            "m.glb: byte 0: not a binary glTF file (no \"glTF\" magic)");
  std::string v1 = glb;
  v1[4] = 1;
  EXPECT_EQ(errorOf(v1), "m.glb: byte 4: binary glTF version 1 is not read (only version 2)");
  EXPECT_NE(errorOf(glb.substr(0, glb.size() - 2)).find("byte 8: the header says the file has"),
            std::string::npos);
  // The total length cut short (as a truncated download whose header was fixed up): the BIN
  // chunk overruns it.
  std::string cut = glb.substr(0, glb.size() - 4);
  const uint32_t length = static_cast<uint32_t>(cut.size());
  cut.replace(8, 4, reinterpret_cast<const char*>(&length), 4);
  EXPECT_NE(errorOf(cut).find("only 4 follow (the file is truncated)"), std::string::npos)
      << errorOf(cut);
  // A stated length shorter than the header (found by the fuzzer).
  EXPECT_EQ(
      errorOf(std::string("glTF\2\0\0\0\2\0\0\0O\0\0\0", 16)),
      "m.glb: byte 8: the header says the file has 2 bytes, too few for a header and a chunk");
  std::string notJson = glb;
  notJson[16] = 'B';
  EXPECT_EQ(errorOf(notJson), "m.glb: byte 16: the first chunk is not the JSON chunk");
}

}  // namespace
}  // namespace prism

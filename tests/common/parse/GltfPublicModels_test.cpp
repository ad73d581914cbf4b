// Every glTF file of a public collection a user can install from Debian (assimp-testmodels:
// assimp's test models, among them Khronos glTF-Sample-Models and glTF-Asset-Generator files,
// glTF 1.0 and deliberately broken ones) loads or is refused with a message naming the file;
// none crashes, hangs or passes the memory limit. Skipped when the package is not installed
// (scripts/setup.sh installs it).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "parse/GltfLoader.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = "/usr/share/assimp/models";

std::vector<fs::path> gltfFiles() {
  std::vector<fs::path> files;
  if (!fs::is_directory(kModels)) return files;
  for (const auto& entry : fs::recursive_directory_iterator(kModels)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (entry.is_regular_file() && (ext == ".gltf" || ext == ".glb")) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string outcome(const fs::path& file) {
  try {
    const ModelDesc model = loadGltfModel(file.string(), {}, MemoryLimit{1ull << 30, "the test"});
    return model.meshes.empty() ? "empty" : "loaded";
  } catch (const SceneError& e) {
    return std::string("refused: ") + e.what();
  }
}

TEST(GltfPublicModels, EveryAssimpTestModelLoadsOrIsRefusedWithAClearMessage) {
  const std::vector<fs::path> files = gltfFiles();
  if (files.empty()) GTEST_SKIP() << kModels << " is missing: apt-get install assimp-testmodels";
  int loaded = 0, refused = 0;
  for (const fs::path& file : files) {
    const std::string result = outcome(file);
    SCOPED_TRACE(file.string() + ": " + result);
    if (result == "loaded") {
      ++loaded;
    } else {
      ++refused;
      EXPECT_TRUE(result.starts_with("refused: " + file.string() + ": ")) << result;
    }
  }
  std::cout << files.size() << " glTF files: " << loaded << " loaded, " << refused << " refused\n";
  EXPECT_GE(loaded, 20);
}

TEST(GltfPublicModels, KnownFilesGiveKnownAnswers) {
  if (!fs::is_directory(kModels / "glTF2")) GTEST_SKIP() << "assimp-testmodels is not installed";
  const fs::path m = kModels / "glTF2";
  const ModelDesc box = loadGltfModel((m / "BoxTextured-glTF-Binary/BoxTextured.glb").string(), {});
  ASSERT_EQ(box.meshes.size(), 1u);
  EXPECT_EQ(box.meshes[0].triangleCount(), 12u);
  ASSERT_EQ(box.textures.size(), 1u);
  EXPECT_GT(box.textures[0].width(), 0);
  const ModelDesc engine =
      loadGltfModel((m / "2CylinderEngine-glTF-Binary/2CylinderEngine.glb").string(), {});
  EXPECT_EQ(engine.triangleCount(), 121496u);
  EXPECT_TRUE(engine.camera);
  EXPECT_NE(outcome(m / "draco/2CylinderEngine.gltf").find("requires KHR_draco_mesh_compression"),
            std::string::npos);
  EXPECT_NE(outcome(m / "RecursiveNodes/RecursiveNodes.gltf").find("the node graph has a cycle"),
            std::string::npos);
  EXPECT_NE(outcome(m / "IndexOutOfRange/IndexOutOfRange.gltf").find("is out of range"),
            std::string::npos);
  EXPECT_NE(outcome(m / "MissingBin/BoxTextured.gltf").find("'BoxTextured0.bin' is missing"),
            std::string::npos);
  EXPECT_NE(outcome(m / "BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb").find("is not finite"),
            std::string::npos);
  EXPECT_NE(outcome(kModels / "glTF/TwoBoxes/TwoBoxes.gltf").find("glTF 1.0 is not read"),
            std::string::npos);
}

}  // namespace
}  // namespace prism

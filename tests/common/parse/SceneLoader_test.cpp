#include "parse/SceneLoader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace prism {
namespace {

namespace fs = std::filesystem;

std::string dataPath(const std::string& relative) {
  return PRISM_TEST_DATA_DIR "/" + relative;
}

// The SceneError that f throws; fails the test when it throws none.
template <typename F>
SceneError errorFrom(F&& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "expected a SceneError";
  return SceneError({}, "");
}

class SceneLoaderFiles : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("prism_loader_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  fs::path dir_;
};

TEST(SceneLoader, YamlByExtension) {
  const std::string path = dataPath("scenes/full.yaml");
  const SceneDescription s = loadScene(path);
  EXPECT_EQ(s.sourcePath, path);
  EXPECT_EQ(s.render.width, 320);
  EXPECT_EQ(s.meshes.size(), 3u);  // the OBJ file was found relative to the scene
}

TEST_F(SceneLoaderFiles, YmlAndUpperCaseExtensionsAreYaml) {
  const std::string text = "render: {width: 17}\n";
  EXPECT_EQ(loadScene(write("a.yml", text)).render.width, 17);
  EXPECT_EQ(loadScene(write("b.YAML", text)).render.width, 17);
}

TEST(SceneLoader, NffByExtension) {
  const SceneDescription s = loadScene(dataPath("nff/balls-s2.nff"));
  EXPECT_FALSE(s.spheres.empty());
  EXPECT_FALSE(s.lights.empty());
}

TEST_F(SceneLoaderFiles, UnsupportedExtensionIsNamed) {
  const std::string path = write("scene.stl", "solid x\n");
  const SceneError e = errorFrom([&] { loadScene(path); });
  EXPECT_EQ(e.loc().file, path);
  EXPECT_EQ(e.loc().line, 0);
  const std::string expected =
      "unsupported scene format '.stl' (expected .yaml, .yml, .nff, or a model: .obj, .ply, "
      ".gltf, .glb)";
  EXPECT_EQ(e.message(), expected);
  EXPECT_EQ(std::string(e.what()), path + ": " + expected);
}

TEST_F(SceneLoaderFiles, MissingExtensionIsNamed) {
  const std::string path = write("scene", "camera: {}\n");
  const SceneError e = errorFrom([&] { loadScene(path); });
  EXPECT_NE(e.message().find("no extension"), std::string::npos) << e.what();
}

TEST_F(SceneLoaderFiles, MissingFileGivesTheSystemReason) {
  const std::string path = (dir_ / "absent.yaml").string();
  const SceneError e = errorFrom([&] { loadScene(path); });
  EXPECT_EQ(e.loc().file, path);
  EXPECT_EQ(e.message(), "cannot read file: No such file or directory");
}

TEST_F(SceneLoaderFiles, DirectoryIsAnError) {
  const fs::path path = dir_ / "folder.yaml";
  fs::create_directories(path);
  const SceneError e = errorFrom([&] { loadScene(path.string()); });
  EXPECT_EQ(e.loc().file, path.string());
  EXPECT_NE(e.message().find("directory"), std::string::npos) << e.what();
}

TEST_F(SceneLoaderFiles, UnreadableFileGivesTheSystemReason) {
  if (::geteuid() == 0) GTEST_SKIP() << "root can read any file";
  const std::string path = write("locked.yaml", "camera: {}\n");
  fs::permissions(path, fs::perms::none);
  const SceneError e = errorFrom([&] { loadScene(path); });
  EXPECT_EQ(e.message(), "cannot read file: Permission denied");
}

TEST_F(SceneLoaderFiles, ReadTextFilePointsAtWhoeverNamedTheFile) {
  const FileLoc from{"scene.yaml", 4, 13};
  const std::string path = (dir_ / "mesh.obj").string();
  const SceneError e = errorFrom([&] { readTextFile(path, from); });
  EXPECT_EQ(e.loc().file, "scene.yaml");
  EXPECT_EQ(e.loc().line, 4);
  EXPECT_EQ(e.loc().column, 13);
  EXPECT_EQ(std::string(e.what()),
            "scene.yaml:4:13: cannot read '" + path + "': No such file or directory");
}

TEST_F(SceneLoaderFiles, ReadTextFileKeepsEveryByte) {
  std::string bytes;
  for (int i = 0; i < 256 * 300; ++i) bytes += static_cast<char>(i * 7);  // > one read buffer
  const std::string path = write("bytes.bin", bytes);
  EXPECT_EQ(readTextFile(path), bytes);
  EXPECT_EQ(readTextFile(write("empty.yaml", "")), "");
}

TEST_F(SceneLoaderFiles, SyntaxErrorsCarryTheFilePath) {
  const std::string path = write("broken.yaml", "camera: {fov: 45\n");
  const SceneError e = errorFrom([&] { loadScene(path); });
  EXPECT_EQ(e.loc().file, path);
  EXPECT_GT(e.loc().line, 0);
  EXPECT_NE(e.message().find("invalid YAML"), std::string::npos) << e.what();
}

}  // namespace
}  // namespace prism

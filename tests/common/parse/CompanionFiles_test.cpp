#include "parse/CompanionFiles.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "fuzz/MemoryFiles.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

TEST(CompanionFiles, ANameIsFoundRelativeToTheFolderWithEitherSeparator) {
  MemoryFiles files;
  files.add("models/textures/wood.png", "x");
  EXPECT_EQ(findCompanionFile("textures/wood.png", "models", files).found,
            "models/textures/wood.png");
  EXPECT_EQ(findCompanionFile("textures\\wood.png", "models", files).found,
            "models/textures/wood.png");
  EXPECT_EQ(findCompanionFile("./textures/../textures/wood.png", "models", files).found,
            "models/textures/wood.png");
}

TEST(CompanionFiles, AnAbsolutePathFromAnotherMachineFallsBackToItsLastPartInTheFolder) {
  MemoryFiles files;
  files.add("models/wood.png", "x");
  EXPECT_EQ(findCompanionFile("C:\\Users\\artist\\wood.png", "models", files).found,
            "models/wood.png");
  EXPECT_EQ(findCompanionFile("/home/artist/wood.png", "models", files).found, "models/wood.png");
  const CompanionFile missing = findCompanionFile("C:\\Users\\artist\\oak.png", "models", files);
  EXPECT_TRUE(missing.found.empty());
  EXPECT_EQ(missing.lookedFor, "models/C:/Users/artist/oak.png");
}

TEST(CompanionFiles, TheDiskHoldsRegularFilesOnly) {
  const fs::path dir =
      fs::temp_directory_path() / ("prism_companion_" + std::to_string(::getpid()));
  fs::create_directories(dir / "sub dir");
  std::ofstream(dir / "sub dir" / "a b.mtl") << "newmtl a\n";
  const CompanionFiles& disk = filesOnDisk();
  EXPECT_TRUE(disk.isFile((dir / "sub dir" / "a b.mtl").string()));
  EXPECT_FALSE(disk.isFile((dir / "sub dir").string()));
  EXPECT_FALSE(disk.isFile((dir / "none.mtl").string()));
  EXPECT_EQ(findCompanionFile("sub dir\\a b.mtl", dir.string(), disk).found,
            (dir / "sub dir" / "a b.mtl").string());
  EXPECT_EQ(disk.readText((dir / "sub dir" / "a b.mtl").string(), {}), "newmtl a\n");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace prism

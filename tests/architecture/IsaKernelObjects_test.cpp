// The kernels of each instruction set (CMakeLists.txt, "Kernels per instruction set") are really
// compiled for it, and isolated: every symbol they define, and every COMDAT group they hold, is
// renamed with the set's suffix, so that the linker cannot let an AVX-512 copy of an inline
// function serve the baseline's callers (which would crash an older CPU). Only the entry points
// (prism_isa_*) keep their names.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "master/PrismProcess.h"

namespace prism {
namespace {

std::vector<std::string> isolatedObjects() {
  std::vector<std::string> objects;
  std::stringstream list(PRISM_ISOLATED_KERNELS);
  for (std::string path; std::getline(list, path, ',');) {
    if (!path.empty()) objects.push_back(path);
  }
  return objects;
}

// "v3" from ".../prism_kernels_v3.o".
std::string setOf(const std::string& object) {
  const size_t at = object.rfind("prism_kernels_");
  return object.substr(at + 14, object.size() - at - 14 - 2);
}

std::vector<std::string> lines(const std::string& command) {
  const test::ProcessRun run = test::runCommand(command);
  EXPECT_EQ(run.exitCode, 0) << command << "\n" << run.output;
  std::vector<std::string> out;
  std::stringstream text(run.output);
  for (std::string line; std::getline(text, line);) out.push_back(line);
  return out;
}

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

TEST(IsaKernelObjects, EverySymbolAndGroupOfASetCarriesItsSuffix) {
  const std::vector<std::string> objects = isolatedObjects();
  if (objects.empty()) GTEST_SKIP() << "this build has no kernels per instruction set";
  for (const std::string& object : objects) {
    const std::string suffix = ".isa_" + setOf(object);
    size_t renamed = 0, entries = 0;
    for (const std::string& line :
         lines(std::string(PRISM_NM) + " --defined-only --extern-only --format=posix " + object)) {
      const std::string symbol = line.substr(0, line.find(' '));
      if (symbol.rfind("prism_isa_" + setOf(object) + "_", 0) == 0) {
        ++entries;
      } else if (endsWith(symbol, suffix)) {
        ++renamed;
      } else {
        ADD_FAILURE() << object << ": " << symbol << " keeps its name";
      }
    }
    EXPECT_GT(renamed, 10u) << object;
    EXPECT_GE(entries, 1u) << object;
    for (const std::string& line : lines(std::string(PRISM_READELF) + " -gW " + object)) {
      if (line.rfind("COMDAT group section", 0) != 0) continue;
      const size_t open = line.find("' [") + 3;
      const std::string signature = line.substr(open, line.find(']', open) - open);
      EXPECT_TRUE(endsWith(signature, suffix)) << object << ": group " << signature;
    }
  }
}

// v3 and v4 use the 256-bit registers; v2 cannot.
TEST(IsaKernelObjects, EachSetIsCompiledForItsInstructions) {
  const std::vector<std::string> objects = isolatedObjects();
  if (objects.empty()) GTEST_SKIP() << "this build has no kernels per instruction set";
  for (const std::string& object : objects) {
    size_t ymm = 0;
    for (const std::string& line : lines(std::string(PRISM_OBJDUMP) + " -d " + object)) {
      ymm += line.find("%ymm") != std::string::npos;
    }
    if (setOf(object) == "v2") {
      EXPECT_EQ(ymm, 0u) << object;
    } else {
      EXPECT_GT(ymm, 100u) << object;
    }
  }
}

}  // namespace
}  // namespace prism

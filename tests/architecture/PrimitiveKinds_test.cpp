// The primitive kinds are listed once (common/geometry/ShapeKinds.h): adding one touches only
// the files docs/README.md's "Adding a primitive" names. The disc, the kind with nothing of its
// own outside its header, is the proof: every source or document that names it must be one of
// those files, and they are few.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace prism {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = PRISM_SOURCE_DIR;

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The files the how-to's bullets begin with ("- `common/geometry/Disc.h`: ...").
std::set<std::string> howToFiles() {
  const std::string doc = readFile(kRoot / "docs/README.md");
  const size_t begin = doc.find("### Adding a primitive");
  const size_t end = doc.find("\n### ", begin + 1);
  const std::string section = doc.substr(begin, end - begin);
  std::set<std::string> files;
  static const std::regex bullet(R"(\n- `([^`]+)`:)");
  for (auto it = std::sregex_iterator(section.begin(), section.end(), bullet);
       it != std::sregex_iterator(); ++it) {
    files.insert((*it)[1].str());
  }
  return files;
}

// Sources and documents (not tests, not the how-to itself) that name the disc primitive: its
// header, its description, its kind, its list or, in a document, its object key.
std::set<std::string> filesNamingTheDisc() {
  static const std::regex code(
      R"(geometry/Disc\.h|\bDiscDesc\b|PrimitiveKind::Disc\b|X\(Disc,|\.discs\b)");
  static const std::regex document(R"(`disc`|\bDiscDesc\b|geometry/Disc\.h)");
  std::set<std::string> found;
  for (const char* top : {"common", "master", "slave", "gui", "docs", "scenes"}) {
    for (const auto& entry : fs::recursive_directory_iterator(kRoot / top)) {
      if (!entry.is_regular_file()) continue;
      const std::string ext = entry.path().extension().string();
      const std::string relative = fs::relative(entry.path(), kRoot).generic_string();
      if (relative == "docs/README.md" || relative.rfind("docs/journal/", 0) == 0) continue;
      const bool isDocument = ext == ".md" || ext == ".yaml";
      if (!isDocument && ext != ".h" && ext != ".cpp") continue;
      const std::string text = readFile(entry.path());
      if (std::regex_search(text, isDocument ? document : code)) found.insert(relative);
    }
  }
  if (std::regex_search(readFile(kRoot / "README.md"), document)) found.insert("README.md");
  return found;
}

TEST(PrimitiveKinds, TheDiscIsNamedOnlyWhereTheHowToSays) {
  const std::set<std::string> listed = howToFiles();
  ASSERT_FALSE(listed.empty()) << "docs/README.md has no 'Adding a primitive' list of files";
  EXPECT_LE(listed.size(), 5u) << "adding a primitive should touch at most 5 files";
  for (const std::string& file : listed) {
    EXPECT_TRUE(fs::exists(kRoot / file)) << "the how-to names " << file << ", which is gone";
  }
  const std::set<std::string> naming = filesNamingTheDisc();
  // The scan sees the kind where it must be: its header and the list.
  EXPECT_TRUE(naming.count("common/geometry/Disc.h") > 0);
  EXPECT_TRUE(naming.count("common/geometry/ShapeKinds.h") > 0);
  EXPECT_TRUE(naming.count("docs/scene-format.md") > 0);
  for (const std::string& file : naming) {
    EXPECT_TRUE(listed.count(file) > 0)
        << file << " names the disc, but docs/README.md's 'Adding a primitive' does not list it: "
        << "a kind should need no code of its own outside its header and the list";
  }
}

}  // namespace
}  // namespace prism

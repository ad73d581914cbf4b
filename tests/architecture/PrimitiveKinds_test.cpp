// The primitive kinds are listed once (common/geometry/ShapeKinds.h): adding one touches only
// the files docs/README.md's "Adding a primitive" names. The disc, the kind with nothing of its
// own outside its header, is the proof: every source or document that names it must be one of
// those files, and they are few.
#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>

#include "architecture/HowToSections.h"

namespace prism {
namespace {

using howto::kRoot;

// Sources and documents that name the disc primitive: its header, its description, its kind,
// its list or, in a document, its object key.
std::set<std::string> filesNamingTheDisc() {
  static const std::regex code(
      R"(geometry/Disc\.h|\bDiscDesc\b|PrimitiveKind::Disc\b|X\(Disc,|\.discs\b)");
  static const std::regex document(R"(`disc`|\bDiscDesc\b|geometry/Disc\.h)");
  return howto::filesNaming(code, document, {"common", "master", "slave", "gui", "docs", "scenes"});
}

TEST(PrimitiveKinds, TheDiscIsNamedOnlyWhereTheHowToSays) {
  const std::set<std::string> listed = howto::listedFiles("### Adding a primitive");
  ASSERT_FALSE(listed.empty()) << "docs/README.md has no 'Adding a primitive' list of files";
  EXPECT_LE(listed.size(), 5u) << "adding a primitive should touch at most 5 files";
  for (const std::string& file : listed) {
    EXPECT_TRUE(std::filesystem::exists(kRoot / file))
        << "the how-to names " << file << ", which is gone";
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

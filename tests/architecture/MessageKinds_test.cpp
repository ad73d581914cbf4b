// Each message is described once (PRISM_WIRE_MESSAGES in common/wire/Messages.h) and handled
// once on each side: adding one touches only the files docs/README.md's "Adding a message"
// names for its phase. Three messages are the proof: PhotonCancel (rank 0 to the slaves while
// the job runs), BuildGeometry (rank 0's set-up broadcast) and SceneAccepted (every slave's
// set-up answer, which rank 0's roll call reads). Every source that names one must be a file
// its list names, and each list is at most three files.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <set>
#include <string>

#include "architecture/HowToSections.h"

namespace prism {
namespace {

// The sources (not tests, not the fuzz seeds) that name the message `name`: its struct or its
// type.
std::set<std::string> sourcesNaming(const std::string& name) {
  const std::regex code("\\b" + name + "Message\\b|MessageType::" + name + "\\b");
  const std::regex noDocument("(?!)");  // matches nothing
  return howto::filesNaming(code, noDocument, {"common", "master", "slave", "gui"});
}

void expectNamedOnlyIn(const std::string& name, const std::set<std::string>& listed,
                       const std::string& section) {
  SCOPED_TRACE(name);
  const std::set<std::string> naming = sourcesNaming(name);
  // The scan sees the message where it must be: its description.
  EXPECT_TRUE(naming.count("common/wire/Messages.h") > 0);
  EXPECT_GE(naming.size(), 3u) << "a message is sent on one side and taken on the other";
  for (const std::string& file : naming) {
    EXPECT_TRUE(listed.count(file) > 0) << file << " names " << name << ", but docs/README.md's '"
                                        << section << "' does not list it";
  }
}

std::set<std::string> checkedList(const std::string& heading) {
  const std::set<std::string> listed = howto::listedFiles(heading);
  EXPECT_FALSE(listed.empty()) << "docs/README.md has no '" << heading << "' list of files";
  EXPECT_LE(listed.size(), 3u) << heading << ": a message should touch at most 3 files";
  for (const std::string& file : listed) {
    EXPECT_TRUE(std::filesystem::exists(howto::kRoot / file))
        << "the how-to names " << file << ", which is gone";
  }
  return listed;
}

TEST(MessageKinds, AMessageOfTheRunIsNamedOnlyWhereTheHowToSays) {
  const std::set<std::string> listed = checkedList("#### A message of the run");
  expectNamedOnlyIn("PhotonCancel", listed, "A message of the run");
}

TEST(MessageKinds, ASetUpMessageIsNamedOnlyWhereTheHowToSays) {
  const std::set<std::string> listed = checkedList("#### A set-up message");
  expectNamedOnlyIn("BuildGeometry", listed, "A set-up message");
  // A message whose fields need more than their types say has its check() beside the others'.
  std::set<std::string> withCheck = listed;
  withCheck.insert("common/wire/Messages.cpp");
  expectNamedOnlyIn("SceneAccepted", withCheck, "A set-up message");
}

}  // namespace
}  // namespace prism

// The checked YAML reader on its own; the scene schema's messages are tested in
// YamlSceneParser_test.cpp.
#include "parse/CheckedYaml.h"

#include <gtest/gtest.h>

#include <functional>

namespace prism::yaml {
namespace {

constexpr std::string_view kKeys[] = {"count", "mode", "size"};

std::string errorOf(const std::function<void()>& read) {
  try {
    read();
  } catch (const SceneError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(CheckedYaml, UnknownAndDuplicateKeysAreReportedWhereTheyAre) {
  const CheckedYaml in("t.yaml");
  const YAML::Node root = in.load("count: 1\ncolour: 2\n");
  EXPECT_EQ(errorOf([&] { in.mapping(root, in.loc(root), "thing", kKeys); }),
            "t.yaml:2:1: unknown thing key 'colour' (expected one of: count, mode, size)");
  const YAML::Node twice = in.load("count: 1\ncount: 2\n");
  EXPECT_EQ(errorOf([&] { in.mapping(twice, in.loc(twice), "thing", kKeys); }),
            "t.yaml:2:1: duplicate key 'count' (first given at 1:1)");
}

TEST(CheckedYaml, TypedGettersCheckRangesAndNames) {
  const CheckedYaml in("t.yaml");
  const YAML::Node root = in.load("count: 300\nmode: photon-map\nsize: -1\n");
  const Mapping m = in.mapping(root, in.loc(root), "thing", kKeys);
  EXPECT_EQ(in.integer(m.require("count"), 0, 300), 300);
  EXPECT_EQ(errorOf([&] { in.integer(m.require("count"), limits::kMaxDepth); }),
            "t.yaml:1:8: 'count' must be at most 256, found 300");
  EXPECT_EQ(in.choice(m.require("mode"), kCausticMethodNames), CausticMethod::PhotonMap);
  EXPECT_EQ(errorOf([&] { in.nonNegative(m.require("size")); }),
            "t.yaml:3:7: 'size' must not be negative, found -1");
  EXPECT_EQ(errorOf([&] { m.require("other"); }), "t.yaml:1:1: thing needs 'other'");
}

TEST(CheckedYaml, OnlyOneDocumentIsAccepted) {
  const CheckedYaml in("t.yaml");
  EXPECT_EQ(errorOf([&] { in.load("a: 1\n---\nb: 2\n"); }),
            "t.yaml:2:1: expected one YAML document, found more (a second starts here)");
}

}  // namespace
}  // namespace prism::yaml

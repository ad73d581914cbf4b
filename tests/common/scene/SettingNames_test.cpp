#include "scene/SettingNames.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

TEST(SettingNames, EitherSpellingAndAnyCaseFindTheValue) {
  for (const char* name : {"photon_map", "photon-map", "Photon-Map", "PHOTON_MAP"}) {
    EXPECT_EQ(kCausticMethodNames.find(name), CausticMethod::PhotonMap) << name;
  }
  EXPECT_EQ(kTriangleTestNames.find("moller-trumbore"), TriangleTest::MollerTrumbore);
  EXPECT_EQ(kCausticMapPathsNames.find("front-face"), CausticMapPaths::FrontFace);
  EXPECT_EQ(kCausticMethodNames.find("photons"), std::nullopt);
}

TEST(SettingNames, AliasesAreAcceptedButNeverListed) {
  EXPECT_EQ(kCausticMethodNames.find("map"), CausticMethod::CausticMap);
  EXPECT_EQ(kCausticMethodNames.list(), "none, photon_map or caustic_map");
  EXPECT_EQ(kCausticMethodNames.list("|", "|"), "none|photon_map|caustic_map");
  EXPECT_EQ(kCausticMethodNames.nameOf(CausticMethod::CausticMap), "caustic_map");
}

TEST(SettingNames, EveryValueOfEveryTableHasOneCanonicalName) {
  EXPECT_EQ(kProjectionNames.names.size(), 2u);
  EXPECT_EQ(kTriangleTestNames.names.size(), 3u);
  EXPECT_EQ(kCausticMethodNames.names.size(), 3u);
  EXPECT_EQ(kCausticMapPathsNames.names.size(), 2u);
  EXPECT_EQ(kPhotonFilterNames.names.size(), 3u);
  EXPECT_EQ(kCausticRoleNames.names.size(), 5u);
  for (const auto& n : kCausticRoleNames.names) {
    EXPECT_EQ(kCausticRoleNames.find(n.name), n.value) << n.name;
  }
}

}  // namespace
}  // namespace prism

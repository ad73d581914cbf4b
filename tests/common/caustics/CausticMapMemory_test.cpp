// The caustic maps' memory, counted with every light's views once the scene is built: a light
// outside its casters has one view, a light among them six, and the check refuses what does not
// fit under the limit before any map is built.
#include "caustics/CausticMapMemory.h"

#include <gtest/gtest.h>

#include "tests/common/caustics/BallOverFloorScene.h"

namespace prism {
namespace {

// The ball-over-floor scene with its light inside the ball: the casters surround it.
SceneDescription lampInsideBall(int resolution = 512) {
  SceneDescription d = test::ballOverFloorScene(1.5f);
  d.lights[0].position = {0, 2, 0};
  d.caustics.method = CausticMethod::CausticMap;
  d.caustics.mapResolution = resolution;
  return d;
}

TEST(CausticMapMemory, CountsSixViewsForALightAmongItsCasters) {
  EXPECT_EQ(kCausticMapBytesPerTexel, 132u);  // receiver 36, caster 28, lookup 32, buffers 36
  SceneDescription outside = test::ballOverFloorScene(1.5f);
  outside.caustics.method = CausticMethod::CausticMap;
  const Scene above(outside);
  EXPECT_EQ(causticMapBytes(above, 512), 1ull * 512 * 512 * 132);
  const Scene inside(lampInsideBall());
  EXPECT_EQ(causticMapBytes(inside, 512), 6ull * 512 * 512 * 132);
  // The maps really have those views (at a resolution that builds quickly).
  CausticSettings small = inside.causticSettings();
  small.mapResolution = 32;
  EXPECT_EQ(CausticMap(inside, 0, small, 1).frustum().views().size(), 6u);
  EXPECT_EQ(CausticMap(above, 0, small, 1).frustum().views().size(), 1u);
}

TEST(CausticMapMemory, RefusesMapsThatDoNotFitWithTheBytesTheViewsAndTheLimit) {
  const MemoryLimit limit{2ull << 30, "test"};
  EXPECT_NO_THROW(checkCausticMapsFit(Scene(lampInsideBall(1024)), limit));  // 792 MiB
  SceneDescription photons = lampInsideBall(4096);
  photons.caustics.method = CausticMethod::PhotonMap;  // no maps: nothing to check
  EXPECT_NO_THROW(checkCausticMapsFit(Scene(photons), limit));
  try {
    checkCausticMapsFit(Scene(lampInsideBall(2048)), limit);
    FAIL() << "6 views of 2048² texels fit in 2 GiB";
  } catch (const ResourceLimitError& e) {
    EXPECT_STREQ(e.what(),
                 "caustic maps of 1 light at 2048 texels a side (6 views) needs 3.1 GiB "
                 "(3321888768 bytes); the memory limit is 2.0 GiB (2147483648 bytes, test): "
                 "reduce --map-resolution");
  }
}

// What the viewer asks before caustic maps are switched on: the same count and message whatever
// the scene's own method, and nothing when the maps fit.
TEST(CausticMapMemory, SaysWhyMapsCannotFitWhateverTheScenesMethod) {
  const MemoryLimit limit{2ull << 30, "test"};
  SceneDescription photons = lampInsideBall(2048);
  photons.caustics.method = CausticMethod::PhotonMap;
  const std::optional<std::string> why = causticMapsRefusal(Scene(photons), limit);
  ASSERT_TRUE(why);
  EXPECT_EQ(*why,
            "caustic maps of 1 light at 2048 texels a side (6 views) needs 3.1 GiB "
            "(3321888768 bytes); the memory limit is 2.0 GiB (2147483648 bytes, test): "
            "reduce --map-resolution");
  photons.caustics.mapResolution = 1024;
  EXPECT_FALSE(causticMapsRefusal(Scene(photons), limit));
}

}  // namespace
}  // namespace prism

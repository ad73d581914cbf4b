#include "scene/SceneValidation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "scene/SettingLimits.h"

namespace prism {
namespace {

std::string refusal(const std::function<void()>& check) {
  try {
    check();
  } catch (const SettingError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SceneValidation, DefaultsAndTheBoundsThemselvesAreAccepted) {
  SceneDescription d;
  EXPECT_NO_THROW(validate(d));
  d.render.samplesPerPixel = static_cast<int>(limits::kSamples.max);
  d.render.maxDepth = static_cast<int>(limits::kMaxDepth.max);
  d.caustics.photons = static_cast<uint64_t>(limits::kPhotons.max);
  EXPECT_NO_THROW(validate(d));
}

TEST(SceneValidation, SamplesAndDepthHaveFixedBounds) {
  RenderSettings s;
  s.samplesPerPixel = 100000;
  EXPECT_EQ(refusal([&] { validate(s); }),
            "render setting 'samples' must be at most 65536, found 100000 (--spp on the command "
            "line)");
  s.samplesPerPixel = 1;
  s.maxDepth = 300;
  EXPECT_EQ(refusal([&] { validate(s); }),
            "render setting 'max_depth' must be at most 256, found 300 (--max-depth on the "
            "command line)");
}

TEST(SceneValidation, CausticSettingsOutsideTheirDomainAreRefused) {
  CausticSettings c;
  c.alpha = 1.0f;
  EXPECT_EQ(refusal([&] { validate(c); }),
            "caustics setting 'alpha' must lie strictly between 0 and 1, found 1.000000");
  c = {};
  c.radius = NAN;
  EXPECT_EQ(refusal([&] { validate(c); }),
            "caustics setting 'radius' must be finite (--gather-radius on the command line)");
  c = {};
  c.photons = (uint64_t{1} << 40) + 1;
  EXPECT_EQ(refusal([&] { validate(c); }),
            "caustics setting 'photons' must be at most 1099511627776, found 1099511627777 "
            "(--photons on the command line)");
  c = {};
  c.mapBlurRadius = -1;
  EXPECT_EQ(refusal([&] { validate(c); }),
            "caustics setting 'map_blur_radius' must be at least 0, found -1 (--map-blur-radius "
            "on the command line)");
}

}  // namespace
}  // namespace prism

#include "math/Aabb.h"

#include <gtest/gtest.h>

#include <limits>

namespace prism {
namespace {

TEST(Aabb, ContainsItsInsideAndFacesButNothingElse) {
  Aabb box;
  EXPECT_FALSE(box.contains(Vec3(0.0f)));  // empty: holds nothing
  box.extend(Vec3(-1.0f, 0.0f, 2.0f));
  box.extend(Vec3(1.0f, 3.0f, 4.0f));
  EXPECT_TRUE(box.contains(Vec3(0.0f, 1.0f, 3.0f)));
  EXPECT_TRUE(box.contains(Vec3(-1.0f, 0.0f, 2.0f)));  // corners and faces belong to it
  EXPECT_TRUE(box.contains(Vec3(1.0f, 3.0f, 4.0f)));
  EXPECT_TRUE(box.contains(Vec3(1.0f, 1.5f, 3.0f)));
  for (int a = 0; a < 3; ++a) {
    for (const float step : {-1e-3f, 1e-3f}) {
      Vec3 outside = step < 0.0f ? box.lower : box.upper;
      outside[a] += step;
      EXPECT_FALSE(box.contains(outside)) << a << " " << step;
    }
    Vec3 nan(0.0f, 1.0f, 3.0f);
    nan[a] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(box.contains(nan)) << a;
  }
}

}  // namespace
}  // namespace prism

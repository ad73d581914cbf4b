#include "caustics/AutomaticGather.h"

#include <gtest/gtest.h>

#include <cmath>

namespace prism {
namespace {

// Nearest photons (nearest first, the photon itself at 0) of a field whose density is `inner`
// out to radius² `edge2` and `outer` beyond: the j-th nearest lies where the disc holds j photons.
std::vector<PhotonNeighbour> neighboursIn(int count, float inner, float outer, float edge2) {
  std::vector<PhotonNeighbour> out;
  const float innerCount = inner * edge2;
  for (int j = 1; j <= count; ++j) {
    const float r2 = j <= innerCount ? j / inner : edge2 + (j - innerCount) / outer;
    out.push_back({static_cast<uint32_t>(j), j == 1 ? 0.0f : r2});
  }
  return out;
}

TEST(AutomaticGather, TheLargestKIsTheNoiseToThePowerMinusTwo) {
  EXPECT_EQ(automaticGatherLargestK(0.05f), 400);
  EXPECT_EQ(automaticGatherLargestK(0.1f), 100);
  EXPECT_EQ(automaticGatherLargestK(0.03f), 1112);  // ⌈1111.1⌉
  EXPECT_EQ(automaticGatherLargestK(1.0f), 1);
}

// Where the density is the same at every scale the photon takes the largest k.
TEST(AutomaticGather, AUniformDensityGetsTheLargestK) {
  const std::vector<PhotonNeighbour> uniform = neighboursIn(400, 1000.0f, 1000.0f, 1.0f);
  EXPECT_FLOAT_EQ(automaticGatherRadius2(uniform, 400, 10.0f), uniform[399].distance2);
  EXPECT_FLOAT_EQ(automaticGatherRadius2(uniform, 100, 10.0f), uniform[99].distance2);
}

// A photon whose nearest 20 lie in a region 10 times denser than beyond: the densities at k = 8
// and 16 agree, at 32 the disc reaches out and the density falls to 0.23 of theirs, outside the
// intervals (±2/√k): the radius is r_16, not r_400.
TEST(AutomaticGather, ADensityThatFallsAwayStopsTheRadiusBeforeIt) {
  const std::vector<PhotonNeighbour> edge = neighboursIn(400, 1000.0f, 100.0f, 0.02f);
  EXPECT_FLOAT_EQ(automaticGatherRadius2(edge, 400, 10.0f), edge[15].distance2);
  // A gentler fall (to 0.8 of the density) stays within the intervals: the largest k.
  const std::vector<PhotonNeighbour> gentle = neighboursIn(400, 1000.0f, 800.0f, 0.02f);
  EXPECT_FLOAT_EQ(automaticGatherRadius2(gentle, 400, 10.0f), gentle[399].distance2);
}

// Fewer photons than k within the cap: the cap ends the ladder where the density still agrees.
TEST(AutomaticGather, TooFewPhotonsWithinTheCapEndAtTheCap) {
  const std::vector<PhotonNeighbour> sparse = neighboursIn(50, 1000.0f, 1000.0f, 1.0f);
  EXPECT_FLOAT_EQ(automaticGatherRadius2(sparse, 400, 0.05f), 0.05f);
  EXPECT_FLOAT_EQ(automaticGatherRadius2({}, 400, 0.05f), 0.05f);
}

}  // namespace
}  // namespace prism

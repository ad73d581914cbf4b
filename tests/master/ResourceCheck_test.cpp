#include "master/ResourceCheck.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

const MemoryLimit k16GiB{16ull << 30, "test"};

TEST(ResourceCheck, RefusesAMillionByMillionImageWithTheMemoryItNeeds) {
  RenderSettings s;
  s.width = 1000000;
  s.height = 1000000;
  try {
    checkRenderFits(s, k16GiB);
    FAIL() << "expected a refusal";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("1000000x1000000"), std::string::npos) << message;
    EXPECT_NE(message.find("21.8 TiB"), std::string::npos) << message;
    EXPECT_NE(message.find("16.0 GiB"), std::string::npos) << message;
  }
}

TEST(ResourceCheck, AcceptsOrdinaryImages) {
  RenderSettings s;
  s.width = 7680;
  s.height = 4320;
  EXPECT_NO_THROW(checkRenderFits(s, k16GiB));
}

// 10^12 photons at 96 bytes each (three 28-byte copies, a 4-byte index, ~8 bytes of tree) is
// 9.6e13 bytes = 87.3 TiB: refused on a 16 GiB machine before anything is traced.
TEST(ResourceCheck, RefusesAbsurdPhotonCountsWithTheMemoryTheyNeed) {
  CausticSettings c;
  c.method = CausticMethod::PhotonMap;
  c.photons = 1000000000000ull;
  EXPECT_EQ(photonMemoryBytes(c), 96000000000000ull);
  try {
    checkCausticsFit(c, k16GiB);
    FAIL() << "expected a refusal";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("87.3 TiB"), std::string::npos) << message;
    EXPECT_NE(message.find("16.0 GiB"), std::string::npos) << message;
    EXPECT_NE(message.find("--photons"), std::string::npos) << message;
  }
  c.photons = 10000000;  // 10 M photons: under 1 GiB
  EXPECT_NO_THROW(checkCausticsFit(c, k16GiB));
  c.method = CausticMethod::None;  // no photon map, no memory, whatever the count says
  c.photons = 1000000000000ull;
  EXPECT_EQ(photonMemoryBytes(c), 0u);
  EXPECT_NO_THROW(checkCausticsFit(c, k16GiB));
}

TEST(ResourceCheck, FormatsBytesInBinaryUnits) {
  EXPECT_EQ(formatBytes(512), "512 B");
  EXPECT_EQ(formatBytes(1536), "1.5 KiB");
  EXPECT_EQ(formatBytes(3.0 * (1ull << 30)), "3.0 GiB");
}

}  // namespace
}  // namespace prism

#include "master/ResourceCheck.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

TEST(ResourceCheck, RefusesAMillionByMillionImageWithTheMemoryItNeeds) {
  RenderSettings s;
  s.width = 1000000;
  s.height = 1000000;
  try {
    checkRenderFits(s, 16ull << 30);
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
  EXPECT_NO_THROW(checkRenderFits(s, 16ull << 30));
}

TEST(ResourceCheck, FormatsBytesInBinaryUnits) {
  EXPECT_EQ(formatBytes(512), "512 B");
  EXPECT_EQ(formatBytes(1536), "1.5 KiB");
  EXPECT_EQ(formatBytes(3.0 * (1ull << 30)), "3.0 GiB");
}

}  // namespace
}  // namespace prism

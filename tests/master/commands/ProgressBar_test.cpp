#include "master/commands/ProgressBar.h"

#include <gtest/gtest.h>

namespace prism {
namespace {

TEST(ProgressBar, ShowsFractionCountsAndEta) {
  const std::string line = ProgressBar::format("render", 25, 100, "tiles", 3.0, 80);
  EXPECT_NE(line.find("25%"), std::string::npos) << line;
  EXPECT_NE(line.find("25/100 tiles"), std::string::npos) << line;
  EXPECT_NE(line.find("ETA 9.0s"), std::string::npos) << line;
  EXPECT_LE(line.size(), 80u);
}

TEST(ProgressBar, FinishedBarIsFullWithoutEta) {
  const std::string line = ProgressBar::format("render", 10, 10, "tiles", 75.0, 60);
  EXPECT_NE(line.find("100%"), std::string::npos);
  EXPECT_EQ(line.find('.'), std::string::npos) << line;  // no empty cells
  EXPECT_EQ(line.find("ETA"), std::string::npos);
  EXPECT_NE(line.find("1m15s"), std::string::npos) << line;
}

}  // namespace
}  // namespace prism

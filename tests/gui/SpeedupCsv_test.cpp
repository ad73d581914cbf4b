#include "gui/SpeedupCsv.h"

#include <gtest/gtest.h>

#include <sstream>

#include "master/analysis/SpeedupReport.h"

namespace prism {
namespace {

TEST(SpeedupCsv, ReadsColumnsInAnyOrderSkippingCommentsAndExtras) {
  const auto points = parseSpeedupCsv(
      "# from prism speedup\n"
      "efficiency, p, note, speedup, seconds\n"
      "\n"
      "0.95, 4, oversubscribed, 3.8, 1.25\n"
      "1.00, 1, serial, 1.0, 4.75\n",
      "t.csv");
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0].processes, 1);  // sorted by p
  EXPECT_DOUBLE_EQ(points[0].seconds, 4.75);
  EXPECT_EQ(points[1].processes, 4);
  EXPECT_DOUBLE_EQ(points[1].speedup, 3.8);
  EXPECT_DOUBLE_EQ(points[1].efficiency, 0.95);
  EXPECT_DOUBLE_EQ(points[1].seconds, 1.25);
}

TEST(SpeedupCsv, KeepsOnlyTheFirstSeriesWhenTheFileHasSeveral) {
  const auto points = parseSpeedupCsv(
      "series,p,seconds,speedup,efficiency\n"
      "dynamic-32,1,2.0,1.0,1.0\n"
      "dynamic-32,2,1.1,1.8,0.9\n"
      "static-32,1,2.1,0.95,0.95\n"
      "static-32,2,1.4,1.4,0.7\n",
      "t.csv");
  ASSERT_EQ(points.size(), 2u);
  EXPECT_DOUBLE_EQ(points[0].seconds, 2.0);
  EXPECT_DOUBLE_EQ(points[1].speedup, 1.8);
}

// What `prism speedup` writes is what the viewer charts: its first series.
TEST(SpeedupCsv, ReadsWhatPrismSpeedupWrites) {
  SpeedupReport report;
  report.serial = {{32, {4.0}, {}}};
  for (Schedule schedule : {Schedule::Dynamic, Schedule::Static}) {
    for (int slaves : {1, 2}) {
      ScalingPoint p;
      p.schedule = schedule;
      p.tileSize = 32;
      p.slaves = slaves;
      p.samples = {schedule == Schedule::Dynamic ? 4.0 / slaves : 5.0 / slaves};
      p.busyFractions.assign(static_cast<size_t>(slaves), {1.0});
      report.points.push_back(p);
    }
  }
  deriveStatistics(report);
  std::stringstream csv;
  writeSpeedupCsv(report, csv);
  const auto points = parseSpeedupCsv(csv.str(), "speedup.csv");
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[1].processes, 2);
  EXPECT_DOUBLE_EQ(points[1].seconds, 2.0);
  EXPECT_DOUBLE_EQ(points[1].speedup, 2.0);
  EXPECT_DOUBLE_EQ(points[1].efficiency, 1.0);
}

void expectError(const std::string& text, const std::string& fragment) {
  try {
    parseSpeedupCsv(text, "t.csv");
    ADD_FAILURE() << "no error for: " << text;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(SpeedupCsv, ErrorsNameTheLine) {
  expectError("p,seconds,speedup\n1,2,3\n", "t.csv:1: the header has no column 'efficiency'");
  expectError("p,seconds,speedup,efficiency\n1,2,x,1\n", "t.csv:2: speedup 'x' is not");
  expectError("p,seconds,speedup,efficiency\n1.5,2,1,1\n", "t.csv:2: p '1.5' is not a whole");
  expectError("p,seconds,speedup,efficiency\n1,2\n", "t.csv:2: 2 fields, the header names 4");
  expectError("p,seconds,speedup,efficiency\n", "a header but no rows");
  expectError("", "empty");
  EXPECT_THROW(readSpeedupCsv("/no/such/file.csv"), std::runtime_error);
}

TEST(SpeedupCsv, TheExampleInDocsLoads) {
  const auto points = readSpeedupCsv(PRISM_SOURCE_DIR "/docs/speedup-default.csv");
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[1].processes, 2);
}

}  // namespace
}  // namespace prism

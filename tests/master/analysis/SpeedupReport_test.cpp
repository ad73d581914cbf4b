#include "master/analysis/SpeedupReport.h"

#include <gtest/gtest.h>

#include <sstream>

namespace prism {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.push_back("");
  return fields;
}

// T1 is the faster serial median (8 s at tile 32); the dynamic series follows Amdahl's law
// with f = 0.1 exactly, so its fit and Karp–Flatt both give 0.1.
SpeedupReport syntheticReport() {
  SpeedupReport r;
  r.scenePath = "scenes/x.yaml";
  r.width = 64;
  r.height = 48;
  r.samplesPerPixel = 1;
  r.ranks = 5;
  r.cores = 2;
  r.repeats = 3;
  r.serial = {{16, {9.0, 8.5, 9.5}, {}}, {32, {8.0, 7.9, 8.4}, {}}};
  for (int p = 1; p <= 4; ++p) {
    ScalingPoint point;
    point.tileSize = 32;
    point.slaves = p;
    const double t = 8.0 / amdahlSpeedup(0.1, p);
    point.samples = {t * 1.01, t, t * 0.98};
    point.busyFractions.assign(static_cast<size_t>(p), {0.9, 0.8, 0.85});
    point.oversubscribed = p + 1 > r.cores;
    point.modelSeconds = t * 1.1;
    r.points.push_back(point);
  }
  ScalingPoint fixed = r.points[1];
  fixed.schedule = Schedule::Static;
  fixed.samples = {8.0, 8.0, 8.0};  // no speedup at all on 2 slaves
  fixed.modelSeconds = 8.8;
  r.points.push_back(fixed);
  return r;
}

TEST(SpeedupReport, StatisticsFromSyntheticTimings) {
  SpeedupReport r = syntheticReport();
  deriveStatistics(r);
  EXPECT_DOUBLE_EQ(r.serialSeconds, 8.0);
  EXPECT_EQ(r.serialTileSize, 32);
  EXPECT_DOUBLE_EQ(r.serial[0].seconds.median, 9.0);
  for (int i = 0; i < 4; ++i) {
    const ScalingPoint& p = r.points[i];
    const double p_ = i + 1;
    EXPECT_NEAR(p.speedup, amdahlSpeedup(0.1, p_), 1e-12);
    EXPECT_NEAR(p.efficiency, amdahlSpeedup(0.1, p_) / p_, 1e-12);
    if (i > 0) {
      EXPECT_NEAR(p.karpFlatt, 0.1, 1e-12);
    }
    EXPECT_NEAR(p.amdahlFraction, 0.1, 1e-12);
    EXPECT_DOUBLE_EQ(p.seconds.max, p.seconds.median * 1.01);
    ASSERT_EQ(p.workerBusy.size(), static_cast<size_t>(i + 1));
    EXPECT_DOUBLE_EQ(p.workerBusy[0], 0.85);
  }
  const ScalingPoint& fixed = r.points[4];
  EXPECT_DOUBLE_EQ(fixed.speedup, 1.0);
  EXPECT_DOUBLE_EQ(fixed.efficiency, 0.5);
  EXPECT_DOUBLE_EQ(fixed.karpFlatt, 1.0);
  EXPECT_DOUBLE_EQ(fixed.amdahlFraction, 1.0);  // its own series
  EXPECT_NEAR(r.modelError(true), 0.1, 1e-12);
  EXPECT_NEAR(r.modelError(false), 0.1, 1e-12);  // p = 1 is the only one not oversubscribed
}

TEST(SpeedupReport, CsvHasTheDocumentedColumnsAndOneRowPerPoint) {
  SpeedupReport r = syntheticReport();
  deriveStatistics(r);
  std::stringstream csv;
  writeSpeedupCsv(r, csv);
  std::string line;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  while (std::getline(csv, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) {
      header = split(line);
    } else {
      rows.push_back(split(line));
    }
  }
  EXPECT_EQ(header, speedupCsvColumns());
  for (const char* needed : {"p", "seconds", "speedup", "efficiency", "karp_flatt",
                             "oversubscribed", "series", "model_seconds"}) {
    EXPECT_NE(std::find(header.begin(), header.end(), needed), header.end()) << needed;
  }
  ASSERT_EQ(rows.size(), r.points.size());
  const auto column = [&](const char* name) {
    return static_cast<size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  for (size_t i = 0; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), header.size()) << i;
    EXPECT_EQ(std::stoi(rows[i][column("p")]), r.points[i].workers());
    EXPECT_NEAR(std::stod(rows[i][column("speedup")]), r.points[i].speedup, 1e-5);
    EXPECT_EQ(rows[i][column("oversubscribed")], r.points[i].oversubscribed ? "yes" : "no");
  }
  EXPECT_EQ(rows[0][column("karp_flatt")], "");  // undefined at p = 1
  EXPECT_EQ(rows[0][column("series")], "dynamic-32");
  EXPECT_EQ(rows[4][column("series")], "static-32");
  EXPECT_EQ(rows[3][column("worker_busy")], "0.8500;0.8500;0.8500;0.8500");
}

TEST(SpeedupReport, TableLabelsOversubscribedPoints) {
  SpeedupReport r = syntheticReport();
  deriveStatistics(r);
  std::stringstream table;
  printSpeedupTable(r, table);
  std::string line;
  int labelled = 0;
  const std::string label = "  oversubscribed";
  while (std::getline(table, line)) {
    labelled += line.size() > label.size() &&
                line.compare(line.size() - label.size(), label.size(), label) == 0;
  }
  EXPECT_EQ(labelled, 4);  // p = 2, 3, 4 dynamic and p = 2 static
}

}  // namespace
}  // namespace prism

// End-to-end tests of `prism sweep` on tiny renders: the real executable, its files and numbers.
#include "master/commands/SweepCommand.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "image/ImageIo.h"
#include "master/PrismProcess.h"

namespace prism {
namespace {

using test::ProcessRun;
using test::runPrism;

class SweepCommandTest : public test::ScratchFolderTest {};

const std::string kSceneDir = std::string(PRISM_SOURCE_DIR) + "/scenes/";

// The CSV as one map of column → value per row.
std::vector<std::map<std::string, std::string>> readCsv(const std::string& path) {
  std::ifstream file(path);
  std::string line;
  std::getline(file, line);
  std::vector<std::string> columns;
  std::stringstream header(line);
  for (std::string c; std::getline(header, c, ',');) columns.push_back(c);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(file, line)) {
    std::stringstream fields(line);
    std::map<std::string, std::string> row;
    size_t i = 0;
    for (std::string f; std::getline(fields, f, ',') && i < columns.size(); ++i)
      row[columns[i]] = f;
    rows.push_back(row);
  }
  return rows;
}

double number(const std::map<std::string, std::string>& row, const std::string& column) {
  return std::stod(row.at(column));
}

// The mirror scene's closed form scores both methods: photon mapping converges to it with the
// flux right; caustic mapping loses all of it (the wall lies outside the light-space view).
TEST_F(SweepCommandTest, MirrorSceneIsScoredAgainstItsClosedForm) {
  const ProcessRun run = runPrism(
      "sweep " + kSceneDir + "caustic-mirror.yaml -W 96 -H 72 -s 1 -r 2 -t 2 -o " + path("mirror") +
      " --families photons,passes,resolution --photons-list 4000,64000 "
      "--passes-list 1,2 --resolution-list 64");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("reference: analytic"), std::string::npos) << run.output;
  const auto rows = readCsv(path("mirror.csv"));
  ASSERT_EQ(rows.size(), 5u);
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("reference"), "analytic");
    EXPECT_EQ(row.at("runs"), "2");
    EXPECT_GT(number(row, "seconds_median"), 0.0);
    EXPECT_GT(number(row, "region_pixels"), 100.0);
  }
  const auto& few = rows[0];
  const auto& many = rows[1];
  EXPECT_EQ(few.at("photons"), "4000");
  EXPECT_LT(number(many, "region_rel_rmse"), number(few, "region_rel_rmse"));
  EXPECT_NEAR(number(many, "region_flux_ratio"), 1.0, 0.05);
  EXPECT_EQ(rows[2].at("family"), "passes");
  EXPECT_EQ(rows[3].at("passes"), "2");
  EXPECT_NEAR(number(rows[3], "region_flux_ratio"), 1.0, 0.05);
  EXPECT_EQ(rows[4].at("method"), "caustic map");
  EXPECT_LT(number(rows[4], "region_flux_ratio"), 0.01);
  int front = 0;
  for (const auto& row : rows) front += row.at("pareto") == "yes";
  EXPECT_GE(front, 1);
  // The chart, with its thumbnails under the panels.
  const ImageRgb chart = readImage(path("mirror.png"));
  EXPECT_GT(chart.width, 1000);
  EXPECT_GT(chart.height, 640);
}

// Without a closed form the progressive reference is rendered once, cached with a key of the
// scene and settings, and reused; its convergence comes with it.
TEST_F(SweepCommandTest, ProgressiveReferenceIsCachedUnderAKeyOfItsSettings) {
  const std::string common =
      "sweep " + kSceneDir + "caustic-glass-sphere.yaml -W 64 -H 48 -s 1 -r 1 -t 2 -o " +
      path("ball") + " --families photons --photons-list 5000 --reference-passes 4 ";
  const ProcessRun first = runPrism(common + "--reference-photons 20000");
  ASSERT_EQ(first.exitCode, 0) << first.output;
  EXPECT_NE(first.output.find("reference: progressive photon map, 4 passes x 20000 photons"),
            std::string::npos)
      << first.output;
  EXPECT_EQ(first.output.find("[cached]"), std::string::npos);
  EXPECT_NE(first.output.find("after 1 passes"), std::string::npos) << first.output;
  EXPECT_NE(first.output.find("after 2 passes"), std::string::npos) << first.output;
  const auto written = std::filesystem::last_write_time(path("ball-reference.exr"));

  const ProcessRun again = runPrism(common + "--reference-photons 20000");
  ASSERT_EQ(again.exitCode, 0) << again.output;
  EXPECT_NE(again.output.find("[cached]"), std::string::npos) << again.output;
  EXPECT_NE(again.output.find("after 2 passes"), std::string::npos) << again.output;
  EXPECT_EQ(std::filesystem::last_write_time(path("ball-reference.exr")), written);

  // The same image given as a file scores the same.
  const std::string scored = readCsv(path("ball.csv")).at(0).at("region_rel_rmse");
  const ProcessRun given = runPrism(common + "--reference " + path("ball-reference.exr"));
  ASSERT_EQ(given.exitCode, 0) << given.output;
  EXPECT_NE(given.output.find("reference: given: "), std::string::npos) << given.output;
  EXPECT_EQ(readCsv(path("ball.csv")).at(0).at("region_rel_rmse"), scored);
  EXPECT_EQ(readCsv(path("ball.csv")).at(0).at("reference"), "given");

  const ProcessRun changed = runPrism(common + "--reference-photons 30000");
  ASSERT_EQ(changed.exitCode, 0) << changed.output;
  EXPECT_EQ(changed.output.find("[cached]"), std::string::npos) << changed.output;
}

TEST_F(SweepCommandTest, BudgetStopsTheSweepAndSaysHowFarItGot) {
  const ProcessRun run = runPrism(
      "sweep " + kSceneDir + "caustic-mirror.yaml -W 64 -H 48 -s 1 -r 3 -t 1 -o " + path("short") +
      " --families photons --photons-list 2000,4000,8000,16000 "
      "--budget-seconds 0.000001");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("budget reached: "), std::string::npos) << run.output;
  EXPECT_LT(readCsv(path("short.csv")).size(), 4u);
}

TEST_F(SweepCommandTest, BadReferencesAreRefusedWithTheReason) {
  const std::string scene = kSceneDir + "caustic-glass-sphere.yaml -W 32 -H 24 -s 1 -o " +
                            path("bad") + " --families resolution --resolution-list 16 ";
  const ProcessRun analytic = runPrism("sweep " + scene + "--reference analytic");
  EXPECT_EQ(analytic.exitCode, 1);
  EXPECT_NE(analytic.output.find("prism: error: no analytic caustics for this scene: a sphere "
                                 "casts caustics"),
            std::string::npos)
      << analytic.output;
  writeImage(ImageRgb(10, 10), path("small.exr"));
  const ProcessRun size = runPrism("sweep " + scene + "--reference " + path("small.exr"));
  EXPECT_EQ(size.exitCode, 1);
  EXPECT_NE(size.output.find("is 10x10, the sweep renders 32x24"), std::string::npos)
      << size.output;
  const ProcessRun family = runPrism("sweep " + scene + "--families colour");
  EXPECT_NE(family.exitCode, 0);
  EXPECT_NE(family.output.find("colour"), std::string::npos) << family.output;
}

}  // namespace
}  // namespace prism

// The points `prism sweep` plans, the Pareto front it marks, and the CSV schema it writes.
#include "master/analysis/SweepPlan.h"

#include <gtest/gtest.h>

#include <sstream>

#include "caustics/AutomaticGather.h"
#include "master/analysis/ParetoFront.h"
#include "master/analysis/SweepReport.h"

namespace prism {
namespace {

SceneDescription photonScene() {
  SceneDescription d;
  d.caustics.method = CausticMethod::PhotonMap;
  d.caustics.photons = 300000;
  d.caustics.gather = 60;
  d.caustics.progressive = true;
  d.caustics.timeBudgetSeconds = 5.0;
  d.render.samplesPerPixel = 2;
  return d;
}

TEST(SweepPlan, EachFamilyChangesOneParameterOfTheScenesSettings) {
  const SceneDescription scene = photonScene();
  SweepValues values;
  values.photons = {1000, 2000};
  values.gather = {5};
  values.passes = {1, 3};
  values.resolution = {64};
  values.blur = {4};
  const auto points = planSweep({SweepFamily::Photons, SweepFamily::Gather, SweepFamily::Passes,
                                 SweepFamily::Resolution, SweepFamily::Blur},
                                values, scene);
  ASSERT_EQ(points.size(), 7u);
  EXPECT_EQ(points[1].caustics.photons, 2000u);
  EXPECT_EQ(points[1].caustics.gather, 60);  // the scene's k
  EXPECT_FALSE(points[1].caustics.progressive);
  EXPECT_EQ(points[1].caustics.timeBudgetSeconds, 0.0);  // a budget would make times meaningless
  EXPECT_EQ(points[2].caustics.gather, 5);
  EXPECT_EQ(points[2].caustics.photons, 300000u);  // the scene's photons
  EXPECT_TRUE(points[4].caustics.progressive);
  EXPECT_EQ(points[4].caustics.passes, 3);
  EXPECT_EQ(points[5].caustics.method, CausticMethod::CausticMap);
  EXPECT_EQ(points[5].caustics.mapResolution, 64);
  EXPECT_EQ(points[6].caustics.mapBlurRadius, 4);
  EXPECT_FLOAT_EQ(points[6].caustics.mapBlurSigma, 2.0f);
  for (const SweepPoint& p : points) EXPECT_EQ(p.samplesPerPixel, 2);
}

// autok sweeps the automatic k by its largest k (the noise 1/√k); k sweeps fixed k even in a
// scene that asks for gather: auto.
TEST(SweepPlan, TheAutomaticKFamilySetsTheNoiseOfItsLargestKAndKFamilyFixesK) {
  SceneDescription scene = photonScene();
  scene.caustics.automaticGather = true;
  SweepValues values;
  values.gather = {50};
  values.autoGather = {25, 400};
  const auto points = planSweep({SweepFamily::Gather, SweepFamily::AutoGather}, values, scene);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_FALSE(points[0].caustics.automaticGather);
  EXPECT_EQ(points[0].caustics.gather, 50);
  for (const SweepPoint& p : {points[1], points[2]}) {
    EXPECT_TRUE(p.caustics.automaticGather);
    EXPECT_EQ(p.caustics.method, CausticMethod::PhotonMap);
    EXPECT_EQ(automaticGatherLargestK(p.caustics.gatherNoise), static_cast<int>(p.value));
  }
  EXPECT_FLOAT_EQ(points[2].caustics.gatherNoise, 0.05f);
}

TEST(SweepPlan, DefaultsCoverEveryMethodAndRefuseValuesOutOfRange) {
  SceneDescription scene;  // no caustics of its own: photon families use 200 000 photons
  const auto points = planSweep(defaultSweepFamilies(), {}, scene);
  EXPECT_EQ(points.size(), 7u + 6u + 6u + 5u + 6u + 5u);
  EXPECT_EQ(points[7].caustics.photons, 200000u);
  SweepValues bad;
  bad.resolution = {8};
  try {
    planSweep({SweepFamily::Resolution}, bad, scene);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "sweep resolution: 8 is outside 16..4096");
  }
}

TEST(ParetoFront, KeepsThePointsNoOtherBeatsOnTimeAndError) {
  //                     0    1    2    3    4    5
  const std::vector<double> time{1.0, 2.0, 3.0, 2.5, 4.0, NAN};
  const std::vector<double> error{0.5, 0.6, 0.2, 0.2, 0.1, 0.01};
  const std::vector<bool> front = paretoFront(time, error);
  EXPECT_EQ(front, (std::vector<bool>{true, false, false, true, true, false}));
}

TEST(SweepCsv, HeaderIsTheSchemaAndEveryRowHasEveryColumn) {
  SweepReport report;
  report.referenceKind = "analytic";
  SweepRow row;
  row.point.family = SweepFamily::Resolution;
  row.point.value = 128;
  row.point.caustics.method = CausticMethod::CausticMap;
  row.point.caustics.mapResolution = 128;
  row.point.samplesPerPixel = 4;
  row.seconds = {0.3, 0.1, 0.2};
  row.cpuSeconds = {0.5, 0.5, 0.6};
  row.image.relRmse = 0.25;
  row.region.relRmse = 0.5;
  row.region.pixels = 42;
  row.image.fluxRatio = NAN;  // written as an empty field
  report.rows = {row};
  markParetoFront(report);
  std::ostringstream csv;
  writeSweepCsv(report, csv);
  std::istringstream lines(csv.str());
  std::string header, line;
  std::getline(lines, header);
  EXPECT_EQ(header,
            "family,method,value,photons,k,passes,map_resolution,map_steps,map_blur_radius,spp,"
            "runs,seconds_median,seconds_min,seconds_max,cpu_seconds_median,rmse,rel_rmse,mrse,"
            "max_error,flux_ratio,region_pixels,region_rmse,region_rel_rmse,region_mrse,"
            "region_max_error,region_flux_ratio,pareto,reference");
  std::getline(lines, line);
  std::vector<std::string> fields;
  std::stringstream split(line);
  for (std::string f; std::getline(split, f, ',');) fields.push_back(f);
  if (line.back() == ',') fields.push_back("");
  ASSERT_EQ(fields.size(), sweepCsvColumns().size()) << line;
  const auto field = [&](const std::string& name) {
    const auto& c = sweepCsvColumns();
    return fields[static_cast<size_t>(std::find(c.begin(), c.end(), name) - c.begin())];
  };
  EXPECT_EQ(field("family"), "resolution");
  EXPECT_EQ(field("method"), "caustic map");
  EXPECT_EQ(field("map_resolution"), "128");
  EXPECT_EQ(field("photons"), "");  // not a photon-map point
  EXPECT_EQ(field("runs"), "3");
  EXPECT_EQ(field("seconds_median"), "0.2");
  EXPECT_EQ(field("seconds_min"), "0.1");
  EXPECT_EQ(field("cpu_seconds_median"), "0.5");
  EXPECT_EQ(field("region_rel_rmse"), "0.5");
  EXPECT_EQ(field("flux_ratio"), "");
  EXPECT_EQ(field("pareto"), "yes");
  EXPECT_EQ(field("reference"), "analytic");
  // The charted error is the region's, or the frame's when the region is empty.
  EXPECT_EQ(report.rows[0].error(SweepMetric::RelRmse), 0.5);
  report.rows[0].region.pixels = 0;
  EXPECT_EQ(report.rows[0].error(SweepMetric::RelRmse), 0.25);
  // The chart names the metric it plots, and where.
  report.metric = SweepMetric::RelRmse;
  const Chart chart = sweepChart(report);
  ASSERT_EQ(chart.panels.size(), 2u);
  EXPECT_EQ(chart.panels[0].yTitle, "relative RMSE");
  EXPECT_EQ(chart.panels[0].title, "Error against time (whole frame)");
  EXPECT_EQ(chart.panels[0].series.at(0).y.at(0), 0.25);
  EXPECT_EQ(sweepChart(SweepReport{}).panels[0].yTitle, "MRSE");
}

}  // namespace
}  // namespace prism

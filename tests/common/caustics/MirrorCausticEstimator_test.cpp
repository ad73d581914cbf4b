// The analytic caustics of flat mirrors: a case worked by hand, the refusals, and agreement
// with the photon tracer's own flux on the closed-form scene.
#include "caustics/MirrorCausticEstimator.h"

#include <gtest/gtest.h>

#include <numeric>

#include "caustics/PhotonTracer.h"
#include "parse/SceneLoader.h"
#include "tests/common/caustics/CausticFluxGrid.h"

namespace prism {
namespace {

// An infinite mirror floor (reflectance 0.5) under a light 1 above it.
SceneDescription mirrorFloor() {
  SceneDescription d;
  MaterialDesc mirror;
  mirror.name = "mirror";
  mirror.diffuse = Color(0.0f);
  mirror.reflectance = Color(0.5f);
  d.materials.push_back(mirror);
  PlaneDesc floor;
  floor.point = Vec3(0.0f);
  floor.normal = Vec3(0, 1, 0);
  d.planes.push_back(floor);
  PointLightDesc light;
  light.position = Vec3(0, 1, 0);
  light.intensity = Color(8.0f);
  d.lights.push_back(light);
  return d;
}

TEST(MirrorCausticEstimator, MirrorImageOfTheLightGivesIrradianceOverDistanceSquared) {
  const SceneDescription d = mirrorFloor();
  const Scene scene(d);
  const MirrorCausticEstimator estimator(d, scene);
  EXPECT_EQ(estimator.facetCount(), 1u);
  // Straight above, facing down: the image is 1 below the mirror, 4 from the point.
  EXPECT_NEAR(estimator.irradiance({0, 3, 0}, {0, -1, 0}).x, 0.5 * 8.0 / 16.0, 1e-6);
  // Off axis: the image at (0, -1, 0), the point at (3, 3, 0): d² = 25, cos θ = 4/5.
  EXPECT_NEAR(estimator.irradiance({3, 3, 0}, {0, -1, 0}).y, 0.5 * 8.0 * 0.8 / 25.0, 1e-6);
  // Facing away from the mirror, or below it: nothing.
  EXPECT_EQ(estimator.irradiance({0, 3, 0}, {0, 1, 0}).x, 0.0f);
  EXPECT_EQ(estimator.irradiance({0, -3, 0}, {0, 1, 0}).x, 0.0f);
}

TEST(MirrorCausticEstimator, AnOccluderBetweenMirrorAndReceiverCastsAShadow) {
  SceneDescription d = mirrorFloor();
  MaterialDesc card;
  card.name = "card";
  d.materials.push_back(card);
  SphereDesc blocker;
  blocker.center = Vec3(0, 2, 0);
  blocker.radius = 0.2f;
  blocker.material = 1;
  d.spheres.push_back(blocker);
  const Scene scene(d);
  const MirrorCausticEstimator estimator(d, scene);
  EXPECT_EQ(estimator.irradiance({0, 3, 0}, {0, -1, 0}).x, 0.0f);
  EXPECT_GT(estimator.irradiance({2, 3, 0}, {0, -1, 0}).x, 0.0f);
}

TEST(MirrorCausticEstimator, RefusesScenesWithoutTheClosedForm) {
  const auto refusal = [](const SceneDescription& d) {
    const Scene scene(d);
    try {
      MirrorCausticEstimator estimator(d, scene);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  SceneDescription glass = mirrorFloor();
  glass.materials[0].transmittance = Color(1.0f);
  EXPECT_NE(refusal(glass).find("transmits light"), std::string::npos);

  SceneDescription ball = mirrorFloor();
  SphereDesc s;
  ball.spheres.push_back(s);  // material 0 reflects: a curved caster
  EXPECT_NE(refusal(ball).find("a sphere casts caustics"), std::string::npos);

  SceneDescription twoPlanes = mirrorFloor();
  PlaneDesc wall;
  wall.normal = Vec3(1, 0, 0);
  twoPlanes.planes.push_back(wall);
  EXPECT_NE(refusal(twoPlanes).find("one plane"), std::string::npos);
}

// scenes/caustic-mirror.yaml: the photons' flux on the back wall, cell by cell, against the
// closed form integrated over the same cells.
TEST(MirrorCausticEstimator, AgreesWithThePhotonTracerOnTheMirrorScene) {
  const SceneDescription d =
      loadScene(std::string(PRISM_SOURCE_DIR) + "/scenes/caustic-mirror.yaml");
  const Scene scene(d);
  const MirrorCausticEstimator estimator(d, scene);
  EXPECT_EQ(estimator.facetCount(), 2u);

  PhotonTracer tracer(scene, 400000, 16);
  const auto photons = tracePhotons(tracer, 0, 0, tracer.photonsPerPass(), 0);
  test::FluxGrid wall;
  wall.corner = {-2.5f, 0.5f, -3.0f};
  wall.u = {5.0f, 0, 0};
  wall.v = {0, 4.0f, 0};
  wall.facing = {0, 0, 1};
  wall.cellsU = 20;
  wall.cellsV = 16;
  const std::vector<double> expected = test::estimatorCellFlux(wall, estimator, 6);
  const std::vector<double> measured = test::photonCellFlux(wall, photons);
  const double expectedTotal = std::accumulate(expected.begin(), expected.end(), 0.0);
  const double measuredTotal = std::accumulate(measured.begin(), measured.end(), 0.0);
  ASSERT_GT(expectedTotal, 0.0);
  EXPECT_NEAR(measuredTotal / expectedTotal, 1.0, 0.01);  // measured 1.003
  double difference = 0.0;
  for (size_t i = 0; i < expected.size(); ++i) difference += std::abs(measured[i] - expected[i]);
  // Cells cut by the patch's edges differ by the midpoint rule's error; the rest by noise.
  EXPECT_LT(difference / expectedTotal, 0.05);  // measured 0.023
}

}  // namespace
}  // namespace prism

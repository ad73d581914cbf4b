#include "render/WhittedIntegrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "master/frame/FrameRenderer.h"
#include "scene/Camera.h"
#include "shading/Optics.h"

namespace prism {
namespace {

// An orthographic camera looking straight down at the y = 0 plane.
SceneDescription topDownScene(int size, float viewWidth) {
  SceneDescription d;
  d.camera.projection = Projection::Orthographic;
  d.camera.position = {0, 5, 0};
  d.camera.lookAt = {0, 0, 0};
  d.camera.up = {0, 0, -1};
  d.camera.width = viewWidth;
  d.render.width = size;
  d.render.height = size;
  d.render.samplesPerPixel = 1;
  return d;
}

MaterialDesc lambert(Color albedo) {
  MaterialDesc m;
  m.diffuse = albedo;
  return m;
}

TEST(WhittedIntegrator, LambertianPlaneUnderPointLightMatchesTheClosedForm) {
  SceneDescription d = topDownScene(33, 6.0f);
  const Color albedo(0.6f, 0.5f, 0.25f);
  d.materials.push_back(lambert(albedo));
  d.planes.push_back({{0, 0, 0}, {0, 1, 0}, 0, {}});
  PointLightDesc light;
  light.position = {0.3f, 2.0f, -0.4f};
  light.intensity = {10.0f, 5.0f, 2.0f};  // W/sr, inverse-square
  d.lights.push_back(light);

  const Scene scene(d);
  const FrameResult frame = renderFrame(scene, {});
  for (int y = 0; y < d.render.height; ++y) {
    for (int x = 0; x < d.render.width; ++x) {
      const Ray ray = scene.camera().generateRay(x + 0.5f, y + 0.5f);
      const Vec3 p = ray.at(ray.origin.y / -ray.direction.y);
      const Vec3 toLight = light.position - p;
      const float distance = glm::length(toLight);
      const float cosTheta = toLight.y / distance;
      // L = albedo/π · I · cosθ / d²
      const Color expected = albedo / kPi * light.intensity * cosTheta / (distance * distance);
      const Color actual = frame.image.at(x, y);
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(actual[c], expected[c], 1e-5f * expected[c]) << x << "," << y << " ch " << c;
      }
    }
  }
}

// The same closed form on a tilted disc seen from above: inside its rim the Lambertian
// radiance, outside it the background (and nothing of the disc leaks past the rim).
TEST(WhittedIntegrator, LambertianDiscUnderPointLightMatchesTheClosedFormInsideItsRim) {
  SceneDescription d = topDownScene(41, 6.0f);
  const Color albedo(0.6f, 0.5f, 0.25f);
  d.materials.push_back(lambert(albedo));
  const Vec3 center(0.2f, 0.1f, -0.3f), normal = glm::normalize(Vec3(0.2f, 1.0f, 0.1f));
  const float radius = 2.2f;
  d.discs.push_back({center, normal, radius, 0, {}, {}});
  d.background = Color(0.125f);
  PointLightDesc light;
  light.position = {0.3f, 2.0f, -0.4f};
  light.intensity = {10.0f, 5.0f, 2.0f};
  d.lights.push_back(light);

  const Scene scene(d);
  const FrameResult frame = renderFrame(scene, {});
  int inside = 0, outside = 0;
  for (int y = 0; y < d.render.height; ++y) {
    for (int x = 0; x < d.render.width; ++x) {
      const Ray ray = scene.camera().generateRay(x + 0.5f, y + 0.5f);
      const float t = glm::dot(normal, center - ray.origin) / glm::dot(normal, ray.direction);
      const Vec3 p = ray.at(t);
      const float fromCenter = glm::length(p - center);
      const Color actual = frame.image.at(x, y);
      if (std::abs(fromCenter - radius) < 0.05f) continue;  // the rim's pixels may go either way
      if (fromCenter > radius) {
        ++outside;
        ASSERT_EQ(actual, d.background) << x << "," << y;
        continue;
      }
      ++inside;
      const Vec3 toLight = light.position - p;
      const float distance = glm::length(toLight);
      const float cosTheta = glm::dot(toLight, normal) / distance;
      const Color expected = albedo / kPi * light.intensity * cosTheta / (distance * distance);
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(actual[c], expected[c], 1e-4f * expected[c]) << x << "," << y << " ch " << c;
      }
    }
  }
  EXPECT_GT(inside, 500);
  EXPECT_GT(outside, 200);
}

TEST(WhittedIntegrator, AttenuationCoefficientsFollowTheFormula) {
  SceneDescription d = topDownScene(9, 2.0f);
  d.materials.push_back(lambert(Color(1.0f)));
  d.planes.push_back({{0, 0, 0}, {0, 1, 0}, 0, {}});
  PointLightDesc light;
  light.position = {0, 3, 0};
  light.intensity = Color(4.0f);
  light.attenuation = {1.0f, 0.5f, 0.25f};
  d.lights.push_back(light);
  const Scene scene(d);
  const FrameResult frame = renderFrame(scene, {});
  // Centre pixel: straight below the light, d = 3, cosθ = 1.
  const float expected = 1.0f / kPi * 4.0f / (1.0f + 0.5f * 3.0f + 0.25f * 9.0f);
  EXPECT_NEAR(frame.image.at(4, 4).x, expected, 1e-6f);
}

TEST(WhittedIntegrator, OccluderCastsAHardShadowAndAmbientRemains) {
  SceneDescription d = topDownScene(21, 4.0f);
  MaterialDesc floor = lambert(Color(0.5f));
  floor.ambient = Color(0.2f);
  d.materials.push_back(floor);
  d.ambientLight = Color(0.1f);
  d.planes.push_back({{0, 0, 0}, {0, 1, 0}, 0, {}});
  PointLightDesc light;
  light.position = {0, 10, 0};
  light.intensity = Color(100.0f);
  d.lights.push_back(light);
  // A sphere above the camera (so unseen) shades a disc centred where the line from the light
  // through its centre meets the floor: (0.5·10/4, 0, 0) = (1.25, 0, 0), radius about 1.25.
  d.spheres.push_back({{0.5f, 6.0f, 0.0f}, 0.5f, 0, {}});
  const Scene scene(d);
  const FrameResult frame = renderFrame(scene, {});
  const int shadowPixel = static_cast<int>((1.25f + 2.0f) / 4.0f * 21.0f);
  EXPECT_NEAR(frame.image.at(shadowPixel, 10).x, 0.2f * 0.1f, 1e-7f);  // ambient term only
  // Pixel (0, 10) is lit, far from the disc: ambient plus the Lambert term.
  const Ray litRay = scene.camera().generateRay(0.5f, 10.5f);
  const Vec3 p = litRay.at(litRay.origin.y / -litRay.direction.y);
  const float distance = glm::length(light.position - p);
  const float lit = 0.2f * 0.1f + 0.5f / kPi * 100.0f * (10.0f / distance) / (distance * distance);
  EXPECT_NEAR(frame.image.at(0, 10).x, lit, 1e-5f);
}

TEST(WhittedIntegrator, GlassSlabTransmitsTheFresnelSeriesAtNormalIncidence) {
  // Camera above a slab bounded by y = 1 and y = 0, looking at a floor that shows exactly its
  // ambient radiance A. Every bounce inside is lossless, so L = A·(1−F)²·Σ F^(2k) = A(1−F)/(1+F).
  SceneDescription d = topDownScene(5, 1.0f);
  d.camera.position = {0, 3, 0};
  d.render.maxDepth = 40;
  d.render.minContribution = 1e-9f;
  MaterialDesc glass;
  glass.diffuse = Color(0.0f);
  glass.transmittance = Color(1.0f);
  glass.ior = 1.5f;
  MaterialDesc floor;
  floor.diffuse = Color(0.0f);
  floor.ambient = Color(1.0f);
  d.materials = {glass, floor};
  d.ambientLight = Color(0.7f);
  d.planes.push_back({{0, 1, 0}, {0, 1, 0}, 0, {}});
  d.planes.push_back({{0, 0, 0}, {0, 1, 0}, 0, {}});
  d.planes.push_back({{0, -1, 0}, {0, 1, 0}, 1, {}});
  const Scene scene(d);
  const FrameResult frame = renderFrame(scene, {});
  const float f = fresnelDielectric(1.0f, 1.0f / 1.5f);
  EXPECT_NEAR(frame.image.at(2, 2).x, 0.7f * (1.0f - f) / (1.0f + f), 1e-5f);
}

TEST(WhittedIntegrator, LosslessGlassUnderUniformSkyConservesRadiance) {
  // A dielectric only redirects light: under a uniform background every pixel sees it exactly.
  SceneDescription d;
  d.camera.position = {0, 0, 4};
  d.render.width = 24;
  d.render.height = 24;
  d.render.maxDepth = 60;
  d.render.minContribution = 1e-7f;
  d.background = Color(0.3f, 0.6f, 0.9f);
  MaterialDesc glass;
  glass.diffuse = Color(0.0f);
  glass.transmittance = Color(1.0f);
  glass.ior = 1.5f;
  d.materials.push_back(glass);
  d.spheres.push_back({{0, 0, 0}, 1.0f, 0, {}});
  const Scene scene(d);
  const FrameResult frame = renderFrame(scene, {});
  for (const Color& c : frame.image.pixels) {
    EXPECT_NEAR(c.x, 0.3f, 2e-4f);
    EXPECT_NEAR(c.z, 0.9f, 6e-4f);
  }
}

TEST(WhittedIntegrator, DepthLimitStopsRecursionBetweenFacingMirrors) {
  SceneDescription d = topDownScene(3, 1.0f);
  d.camera.position = {0, 0.5f, 0};
  d.background = Color(1.0f);
  MaterialDesc mirror;
  mirror.diffuse = Color(0.0f);
  mirror.reflectance = Color(0.5f);
  d.materials.push_back(mirror);
  d.planes.push_back({{0, 0, 0}, {0, 1, 0}, 0, {}});
  d.planes.push_back({{0, 1, 0}, {0, -1, 0}, 0, {}});
  d.render.maxDepth = 6;
  d.render.minContribution = 0.0f;
  const Scene scene(d);
  RayCounters rays;
  const WhittedIntegrator integrator(scene);
  const Color c = integrator.radiance(scene.camera().generateRay(1.5f, 1.5f), 0, Color(1.0f), rays);
  EXPECT_EQ(rays.secondary, 6u);
  EXPECT_FLOAT_EQ(c.x, 0.0f);  // every path ends on a black mirror, never escapes
}

// A mirror ball (no diffuse albedo, a narrow Phong highlight) under a light straight above it,
// seen from above along vertical rays: the light reaches every point of the upper half, but only
// near the top does the highlight face the viewer. Elsewhere the light adds exactly nothing,
// blocked or not, and no shadow ray is traced for it; where it adds something the shadow ray is
// traced and the highlight is the closed form. The packet path skips the same rays.
TEST(WhittedIntegrator, NoShadowRayWhereTheLightAddsExactlyNothing) {
  SceneDescription d = topDownScene(8, 2.0f);
  MaterialDesc mirror;
  mirror.diffuse = Color(0.0f);
  mirror.specular = Color(0.8f);
  mirror.shininess = 400.0f;
  d.materials.push_back(mirror);
  d.spheres.push_back({{0, 0, 0}, 1.0f, 0, {}});
  PointLightDesc light;
  light.position = {0, 10, 0};
  light.intensity = Color(81.0f);
  d.lights.push_back(light);
  const Scene scene(d);
  const WhittedIntegrator integrator(scene);
  const auto downAt = [](float x) { return Ray{{x, 5, 0}, {0, -1, 0}}; };

  // The top: the highlight looks straight at the viewer, pow(1, 400) = 1, and the light is 9
  // units away.
  RayCounters top;
  const Color peak = integrator.radiance(downAt(0.0f), 0, Color(1.0f), top);
  EXPECT_EQ(top.shadow, 1u);
  EXPECT_NEAR(peak.x, 0.8f * 81.0f / 81.0f, 1e-4f);

  // Two points the light reaches (above the horizon of the ball as the light sees it): at
  // x = 0.8 the highlight turns away (r·v < 0), at x = 0.4 it faces the viewer but so
  // obliquely that pow(r·v, 400) is 0 in float.
  for (const float x : {0.4f, 0.8f}) {
    const Vec3 p(x, std::sqrt(1.0f - x * x), 0.0f), n = p;
    const Vec3 toLight = glm::normalize(light.position - p);
    ASSERT_GT(glm::dot(n, toLight), 0.0f) << x;
    const float rv = glm::dot(reflect(-toLight, n), Vec3(0, 1, 0));
    if (x < 0.5f) {
      ASSERT_GT(rv, 0.0f);
      ASSERT_EQ(std::pow(rv, 400.0f), 0.0f);
    } else {
      ASSERT_LT(rv, 0.0f);
    }
    RayCounters rays;
    EXPECT_EQ(integrator.radiance(downAt(x), 0, Color(1.0f), rays), Color(0.0f)) << x;
    EXPECT_EQ(rays.shadow, 0u) << x;
  }

  // Eight rays from the top outwards as one packet: the same answers and the same rays.
  Ray rays[Scene::kPacketSize];
  Color single[Scene::kPacketSize], packet[Scene::kPacketSize];
  RayCounters singleCount, packetCount;
  for (int i = 0; i < Scene::kPacketSize; ++i) {
    rays[i] = downAt(0.1f * static_cast<float>(i));
    single[i] = integrator.radiance(rays[i], 0, Color(1.0f), singleCount);
  }
  integrator.radiance8(rays, Scene::kPacketSize, packet, packetCount);
  for (int i = 0; i < Scene::kPacketSize; ++i) EXPECT_EQ(packet[i], single[i]) << i;
  EXPECT_EQ(packetCount.shadow, singleCount.shadow);
  EXPECT_GT(singleCount.shadow, 0u);
  EXPECT_LT(singleCount.shadow, static_cast<uint64_t>(Scene::kPacketSize));
}

// Records the footprints the integrator asks the caustic estimate for.
class FootprintProbe : public CausticEstimator {
 public:
  Color irradiance(const Vec3&, const Vec3&) const override { return Color(0.0f); }
  Color irradianceAt(const SurfaceHit&, const PixelFootprint& footprint) const override {
    footprints.push_back(footprint);
    return Color(0.0f);
  }
  bool usesFootprint() const override { return true; }
  mutable std::vector<PixelFootprint> footprints;
};

void expectNear(const Vec3& got, const Vec3& expected, float tolerance) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], expected[i], tolerance) << "component " << i;
}

// The footprints the caustic estimate is asked for along ray, traced in scene d.
std::vector<PixelFootprint> footprintsAlong(const SceneDescription& d, const Ray& ray,
                                            const RayDifferential& differential) {
  const Scene scene(d);
  FootprintProbe probe;
  const WhittedIntegrator integrator(scene, {true, &probe});
  RayCounters rays;
  integrator.radiance(ray, 0, Color(1.0f), rays, differential);
  return probe.footprints;
}

// A differential that moves the ray's origin by `width` and turns it by `angle` per pixel, along
// x for a step in x and along z for a step in y.
RayDifferential perPixel(float width, float angle) {
  return {true, {width, 0, 0}, {0, 0, width}, {angle, 0, 0}, {0, 0, angle}};
}

// A scene with two materials: 0 a perfect mirror, 1 a grey Lambertian receiver.
SceneDescription mirrorAndReceiverMaterials() {
  SceneDescription d;
  MaterialDesc mirror;
  mirror.diffuse = Color(0.0f);
  mirror.reflectance = Color(1.0f);
  d.materials.push_back(mirror);
  d.materials.push_back(lambert(Color(0.5f)));
  return d;
}

// The pixel's footprint where its ray meets a receiver, through a mirror: each pixel step
// turns the ray by 0.01 rad, so after 4 units of path (1 down to the mirror, 3 up to the
// ceiling) the footprint's sides are 0.04 long; at 60° from the normal the side in the plane of
// incidence is twice as long (8 units of path: 0.08 across, 0.16 along).
TEST(WhittedIntegrator, TheCausticEstimateGetsThePixelsFootprintThroughMirrors) {
  SceneDescription d = mirrorAndReceiverMaterials();
  d.planes.push_back({{0, 0, 0}, {0, 1, 0}, 0, {}});  // a mirror floor 1 below the camera
  d.planes.push_back({{0, 3, 0}, {0, 1, 0}, 1, {}});  // a receiving ceiling 3 above the floor
  const Ray down{{0, 1, 0}, {0, -1, 0}};
  std::vector<PixelFootprint> f = footprintsAlong(d, down, perPixel(0.0f, 0.01f));
  ASSERT_EQ(f.size(), 1u);  // the ceiling; the mirror receives no caustic
  ASSERT_TRUE(f[0].valid);
  expectNear(f[0].a, {0.04f, 0, 0}, 1e-6f);
  expectNear(f[0].b, {0, 0, 0.04f}, 1e-6f);

  const Vec3 slanted = glm::normalize(Vec3(std::sqrt(3.0f), -1.0f, 0.0f));
  RayDifferential slantedTurn = perPixel(0.0f, 0.01f);
  slantedTurn.dDdx = 0.01f * glm::normalize(Vec3(0.5f, std::sqrt(3.0f) * 0.5f, 0.0f));
  f = footprintsAlong(d, Ray{{0, 1, 0}, slanted}, slantedTurn);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_NEAR(glm::length(f[0].a), 0.16f, 1e-5f);
  EXPECT_NEAR(glm::length(f[0].b), 0.08f, 1e-5f);
  EXPECT_NEAR(f[0].area(), 0.0128f, 1e-6f);

  // A convex mirror (the top of a sphere of radius 10) spreads the rays more: at the mirror the
  // footprint's side is 0.01 and the normal turns by 0.01/10 across it, so the reflected rays
  // spread by 0.01 + 2·0.001 per pixel; 3 more units of path: 0.01 + 3·0.012 = 0.046.
  d.planes.erase(d.planes.begin());
  d.spheres.push_back({{0, -10, 0}, 10.0f, 0, {}, CausticRole::Auto});
  f = footprintsAlong(d, down, perPixel(0.0f, 0.01f));
  ASSERT_EQ(f.size(), 1u);
  ASSERT_TRUE(f[0].valid);
  expectNear(f[0].a, {0.046f, 0, 0}, 1e-5f);
  expectNear(f[0].b, {0, 0, 0.046f}, 1e-5f);

  // A cone's curvature is not modelled: past it the estimate is taken at the point.
  d.spheres.clear();
  ConeDesc cylinder;
  cylinder.base = {-20, -10, 0};
  cylinder.apex = {20, -10, 0};
  cylinder.baseRadius = cylinder.apexRadius = 10.0f;
  cylinder.material = 0;
  d.cones.push_back(cylinder);
  f = footprintsAlong(d, down, perPixel(0.0f, 0.01f));
  ASSERT_EQ(f.size(), 1u);
  EXPECT_FALSE(f[0].valid);
}

// The sample's cell (its offset to its stratum's centre and the stratum's size, in pixels)
// travels with the differentials: the footprint met through a mirror, and through a glass ball,
// gives the cell about where its centre maps (PixelFootprint::offset, sampleCell).
TEST(WhittedIntegrator, TheSamplesCellTravelsThroughMirrorsAndGlass) {
  SceneDescription d = mirrorAndReceiverMaterials();
  d.planes.push_back({{0, 0, 0}, {0, 1, 0}, 0, {}});  // a mirror floor 1 below the camera
  d.planes.push_back({{0, 3, 0}, {0, 1, 0}, 1, {}});  // a receiving ceiling
  RayDifferential sample = perPixel(0.0f, 0.01f);
  sample.toCellCentre = Vec2(0.125f, -0.1875f);
  sample.cell = Vec2(0.5f, 0.5f);
  std::vector<PixelFootprint> f = footprintsAlong(d, Ray{{0, 1, 0}, {0, -1, 0}}, sample);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].toCellCentre, sample.toCellCentre);
  EXPECT_EQ(f[0].cell, sample.cell);
  expectNear(f[0].offset(), 0.125f * f[0].a - 0.1875f * f[0].b, 1e-7f);
  expectNear(f[0].sampleCell().a, 0.5f * f[0].a, 1e-7f);
  expectNear(f[0].sampleCell().b, 0.5f * f[0].b, 1e-7f);

  // A clear ball (index 1.5) between the camera and a receiving floor.
  SceneDescription glass = mirrorAndReceiverMaterials();
  glass.materials[0].reflectance = Color(0.0f);
  glass.materials[0].transmittance = Color(1.0f);
  glass.materials[0].ior = 1.5f;
  glass.spheres.push_back({{0, 2, 0}, 1.0f, 0, {}, CausticRole::Auto});
  glass.planes.push_back({{0, 0, 0}, {0, 1, 0}, 1, {}});
  f = footprintsAlong(glass, Ray{{0.1f, 5, 0}, {0, -1, 0}}, sample);
  ASSERT_FALSE(f.empty());
  ASSERT_TRUE(f.back().valid);
  EXPECT_EQ(f.back().toCellCentre, sample.toCellCentre);
  EXPECT_EQ(f.back().cell, sample.cell);
}

// A mirror ball too small for the pixel's footprint on it (reach over a quarter of its radius)
// turns the pixel's rays by more than the first-order model follows: past it the estimate is
// taken at the point, not averaged over a footprint that would cover much of the scene. The
// footprint here is 0.01 on a side at the ball (reach 0.01).
TEST(WhittedIntegrator, AMirrorBallTooSmallForThePixelsFootprintEndsIt) {
  // The smallest ball that passes this footprint on (0.04 at a quarter of the radius).
  const float smallest = 0.01f / WhittedIntegrator::kMaxFootprintReachOnSphere;
  SceneDescription d = mirrorAndReceiverMaterials();
  d.planes.push_back({{0, 3, 0}, {0, 1, 0}, 1, {}});  // the receiving ceiling
  const Ray down{{0, 1, 0}, {0, -1, 0}};
  for (const float scale : {2.0f, 1.002f, 0.998f, 0.25f, 0.1f}) {
    const float radius = scale * smallest;
    d.spheres = {{{0, -radius, 0}, radius, 0, {}, CausticRole::Auto}};
    const std::vector<PixelFootprint> f = footprintsAlong(d, down, perPixel(0.0f, 0.01f));
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].valid, scale >= 1.0f) << "ball of radius " << radius;
    if (f[0].valid) {
      // 0.01 + 2·0.01/R turn per pixel, 3 units of path from the ball to the ceiling.
      EXPECT_NEAR(f[0].a.x, 0.01f + 3.0f * (0.01f + 0.02f / radius), 1e-3f);
    }
  }
}

// A clear glass ball (radius 1, index 1.5, no Fresnel reflection) with its centre `height`
// above a grey Lambert floor at y = 0.
SceneDescription glassBallOverFloor(float height) {
  SceneDescription d;
  MaterialDesc glass;
  glass.diffuse = Color(0.0f);
  glass.transmittance = Color(1.0f);
  glass.ior = 1.5f;
  glass.fresnel = false;
  d.materials.push_back(glass);
  d.materials.push_back(lambert(Color(0.5f)));
  d.spheres.push_back({{0, height, 0}, 1.0f, 0, {}, CausticRole::Auto});
  d.planes.push_back({{0, 0, 0}, {0, 1, 0}, 1, {}});
  return d;
}

// Through a glass ball (radius 1, index 1.5) a parallel bundle converges as if bent at the
// ball's centre by a lens of focal length nR/(2(n − 1)) = 1.5 (a ball lens's principal planes
// meet at its centre): on a floor 2.5 below the centre a pixel of width 0.01 has become
// 0.01·|1 − 2.5/1.5| = 0.00667 wide, flipped.
TEST(WhittedIntegrator, AGlassBallFocusesThePixelsFootprintAsABallLens) {
  const SceneDescription d = glassBallOverFloor(2.5f);
  const std::vector<PixelFootprint> f =
      footprintsAlong(d, Ray{{0, 5, 0}, {0, -1, 0}}, perPixel(0.01f, 0.0f));
  ASSERT_EQ(f.size(), 1u);
  ASSERT_TRUE(f[0].valid);
  const float side = 0.01f * (2.5f / 1.5f - 1.0f);
  expectNear(f[0].a, {-side, 0, 0}, 2e-5f);
  expectNear(f[0].b, {0, 0, -side}, 2e-5f);
}

// The glass ball's caustic seen from straight above (tests/bench/scenes/glass-ball-top.yaml:
// camera 10 above the floor, 30° over 1024 pixels, the ball of radius 1 and index 1.5 centred 2
// above the floor): the first-order footprint of a pixel seen through the ball, carried by the
// ray differentials, against the quadrilateral its four corner rays trace through the ball
// (exact refraction, double precision). At the focus (the axis) a pixel covers 0.35 mm of floor
// and across the ball up to 2.6 mm; the two areas agree within 0.2 %, so the pixel footprint
// is not what the remaining error at the focus came from (docs/accuracy.md).
TEST(WhittedIntegrator, APixelsFootprintThroughTheBallIsTheOneItsCornerRaysTrace) {
  SceneDescription d = glassBallOverFloor(2.0f);
  d.camera.position = {0, 10, 0};
  d.camera.lookAt = {0, 0, 0};
  d.camera.up = {0, 0, -1};
  d.camera.fovDegrees = 30.0f;
  constexpr int kSize = 1024;
  const Camera camera(d.camera, kSize, kSize);
  // Where the ray through image point (x, y) meets the floor through the ball, in x and z.
  const auto throughBall = [&](double x, double y) {
    const double t = std::tan(15.0 * 3.14159265358979323846 / 180.0);
    const double u = (2.0 * x / kSize - 1.0) * t, v = (1.0 - 2.0 * y / kSize) * t;
    double o[3] = {0, 10, 0}, dir[3] = {u, -1.0, -v};  // right = +x, up = −z
    const auto normalise = [](double* a) {
      const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
      for (int i = 0; i < 3; ++i) a[i] /= l;
    };
    normalise(dir);
    for (int side = 0; side < 2; ++side) {  // enter, leave
      const double oc[3] = {o[0], o[1] - 2.0, o[2]};
      const double b = oc[0] * dir[0] + oc[1] * dir[1] + oc[2] * dir[2];
      const double c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - 1.0;
      const double hit = side == 0 ? -b - std::sqrt(b * b - c) : -b + std::sqrt(b * b - c);
      for (int i = 0; i < 3; ++i) o[i] += hit * dir[i];
      double n[3] = {o[0], o[1] - 2.0, o[2]};  // outward, unit
      const double eta = side == 0 ? 1.0 / 1.5 : 1.5;
      if (side == 1) n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];  // facing the ray
      const double cosI = -(n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2]);
      const double cosT = std::sqrt(1.0 - eta * eta * (1.0 - cosI * cosI));
      for (int i = 0; i < 3; ++i) dir[i] = eta * dir[i] + (eta * cosI - cosT) * n[i];
    }
    const double toFloor = -o[1] / dir[1];
    return std::pair<double, double>{o[0] + toFloor * dir[0], o[2] + toFloor * dir[2]};
  };
  // Pixels at the focus, and 40 and 160 pixels from it (the ball's image is 240 pixels wide).
  for (const int offset : {0, 40, 160}) {
    const int px = kSize / 2 + offset, py = kSize / 2 + offset / 2;
    const Ray ray = camera.generateRay(px + 0.5f, py + 0.5f);
    const std::vector<PixelFootprint> f = footprintsAlong(d, ray, camera.pixelDifferential(ray));
    ASSERT_EQ(f.size(), 1u) << offset;
    ASSERT_TRUE(f[0].valid) << offset;
    const auto c00 = throughBall(px, py), c10 = throughBall(px + 1, py);
    const auto c11 = throughBall(px + 1, py + 1), c01 = throughBall(px, py + 1);
    const double cornerArea = 0.5 * std::fabs((c11.first - c00.first) * (c01.second - c10.second) -
                                              (c01.first - c10.first) * (c11.second - c00.second));
    EXPECT_NEAR(f[0].area() / cornerArea, 1.0, 2e-3) << "pixel " << offset << " from the axis";
  }
}

// A sky far finer than the pixels that see it, directly and in a mirror ball: a checkerboard of
// 2 × 2-texel cells on 256² faces, seen by a 24 × 24 camera with a 90° view (about 8 texels a
// pixel; the ball's reflection shrinks it further). Each camera ray carrying its cone reads the
// mip levels of its footprint; against a reference averaging 16 × 16 rays a pixel,
// its error is a fraction of what one finest-level lookup a pixel gives (a coin toss between
// the cells: aliasing).
TEST(WhittedIntegrator, EscapingRaysFilterTheSkyOverTheirFootprint) {
  SceneDescription d;
  d.camera.position = {0, 0, 0};
  d.camera.lookAt = {0, 0, -1};
  d.camera.fovDegrees = 90.0f;
  d.render.width = d.render.height = 24;
  d.render.maxDepth = 2;
  CubeMapDesc sky;
  for (ImageRgb& face : sky.faces) {
    face = ImageRgb(256, 256);
    for (int y = 0; y < 256; ++y) {
      for (int x = 0; x < 256; ++x) face.at(x, y) = Color(static_cast<float>((x / 2 + y / 2) % 2));
    }
  }
  d.environment = sky;
  MaterialDesc mirror;
  mirror.diffuse = Color(0.0f);
  mirror.reflectance = Color(1.0f);
  d.materials.push_back(mirror);
  d.spheres.push_back({{0.6f, -0.3f, -3.0f}, 0.8f, 0, {}});
  const Scene scene(d);
  const WhittedIntegrator integrator(scene);
  ASSERT_TRUE(integrator.usesCones());
  ASSERT_FALSE(integrator.usesDifferentials());  // no caustics: only the cones are carried
  const Camera camera(d.camera, 24, 24);

  double filteredError = 0.0, pointError = 0.0;
  int ballPixels = 0;
  for (int y = 0; y < 24; ++y) {
    for (int x = 0; x < 24; ++x) {
      RayCounters rays;
      Color reference(0.0f);
      constexpr int kSide = 16;
      for (int j = 0; j < kSide; ++j) {
        for (int i = 0; i < kSide; ++i) {
          const Ray ray = camera.generateRay(static_cast<float>(x) + (i + 0.5f) / kSide,
                                             static_cast<float>(y) + (j + 0.5f) / kSide);
          reference += integrator.radiance(ray, 0, Color(1.0f), rays);
        }
      }
      reference /= static_cast<float>(kSide * kSide);
      const Ray ray =
          camera.generateRay(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const Color filtered =
          integrator.radiance(ray, 0, Color(1.0f), rays, {}, camera.pixelCone(ray));
      const Color point = integrator.radiance(ray, 0, Color(1.0f), rays);
      filteredError += glm::dot(filtered - reference, filtered - reference) / 3.0f;
      pointError += glm::dot(point - reference, point - reference) / 3.0f;
      HitRecord hit;
      ballPixels += scene.intersect(ray, hit);
    }
  }
  EXPECT_GT(ballPixels, 30);  // the reflections are part of the test
  const double filteredRmse = std::sqrt(filteredError / (24 * 24));
  const double pointRmse = std::sqrt(pointError / (24 * 24));
  EXPECT_GT(pointRmse, 0.3);  // the sky aliases unfiltered
  // Measured with the cones: 0.006 against 0.33 (with differentials it was 0.077).
  RecordProperty("filtered_rmse", std::to_string(filteredRmse));
  EXPECT_LT(filteredRmse, 0.25 * pointRmse) << "point RMSE " << pointRmse;
}

}  // namespace
}  // namespace prism

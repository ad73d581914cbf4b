// Caustic mapping against closed forms and against photon mapping: an index-1 sphere passes the
// light unchanged (the map must give the direct irradiance I·cos θ/d²), energy is never created,
// the maps are finite, and on the glass-sphere scene the error against a converged photon
// map falls as the resolution rises.
#include "caustics/CausticMap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <random>
#include <vector>

#include "caustics/CausticMapEstimator.h"
#include "caustics/PhotonTracer.h"
#include "parse/SceneLoader.h"
#include "tests/common/caustics/BallOverFloorScene.h"

namespace prism {
namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kIntensity = test::kBallLightIntensity;
constexpr float kLightHeight = test::kBallLightHeight;

// A sphere of radius 1 at (0, 2, 0), transmittance 1 and index `ior`, a diffuse floor y = 0 and
// a point light of intensity I at (0, 4, 0), as in PhotonTracer_test's energy scene.
SceneDescription sphereScene(float ior, int resolution, int blurRadius) {
  SceneDescription d = test::ballOverFloorScene(ior);
  d.caustics.method = CausticMethod::CausticMap;
  d.caustics.mapResolution = resolution;
  d.caustics.mapBlurRadius = blurRadius;
  return d;
}

TEST(CausticMap, IndexOneSphereGivesTheDirectIrradianceUnderIt) {
  for (const CausticMapPaths paths : {CausticMapPaths::Traced, CausticMapPaths::FrontFace}) {
    SceneDescription d = sphereScene(1.0f, 256, 2);
    d.caustics.mapPaths = paths;
    const Scene scene(d);
    const CausticMap map(scene, 0, scene.causticSettings(), 0);
    ASSERT_FALSE(map.empty());
    EXPECT_FALSE(map.frustum().cube());
    // The shadow of the sphere reaches x = 4·tan 30° = 2.31; stay inside it, off its rim.
    for (const float x : {0.0f, 0.37f, 0.81f, 1.2f, 1.6f}) {
      const float d2 = kLightHeight * kLightHeight + x * x;
      const float expected = kIntensity * kLightHeight / (d2 * std::sqrt(d2));
      const Color e = map.irradiance({x, 0.0f, 0.3f * x}, {0, 1, 0});
      const float dz2 = d2 + 0.09f * x * x;
      const float expectedZ = kIntensity * kLightHeight / (dz2 * std::sqrt(dz2));
      EXPECT_NEAR(e.x, expectedZ, 0.01f * expected) << "x = " << x;
      EXPECT_FLOAT_EQ(e.x, e.z);
    }
    // From below the floor, or at a point the light does not see first: nothing.
    EXPECT_EQ(map.irradiance({0.2f, 0.0f, 0.0f}, {0, -1, 0}).x, 0.0f);
    EXPECT_EQ(map.irradiance({0.0f, -1.0f, 0.0f}, {0, 1, 0}).x, 0.0f);
  }
}

// Every path the light takes through the caster texels carries at most their flux, and the
// caster texels hold the flux of the cone the sphere subtends: I·2π(1 − cos 30°).
TEST(CausticMap, NoEnergyIsCreatedAndTheMapsAreFinite) {
  for (const float ior : {1.0f, 1.5f}) {
    const Scene scene(sphereScene(ior, 128, 2));
    const CausticMap map(scene, 0, scene.causticSettings(), 0);
    const CausticMapStats& s = map.stats();
    const double cone = kIntensity * 2.0 * kPiD * (1.0 - std::cos(kPiD / 6.0));
    EXPECT_NEAR(s.emittedFlux, cone, 0.01 * cone);
    EXPECT_LE(s.splattedFlux, s.emittedFlux * (1.0 + 1e-6));
    EXPECT_GT(s.splatted, 0u);
    // The flux the irradiance map holds: Σ E·area over the receiver texels (before any blur).
    SceneDescription unblurred = sphereScene(ior, 128, 0);
    const Scene scene0(unblurred);
    const CausticMap map0(scene0, 0, scene0.causticSettings(), 0);
    const int n = map0.frustum().resolution();
    double held = 0.0;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const ReceiverTexel& t = map0.receivers().at(0, i, j);
        const Color e = map0.texelIrradiance(static_cast<size_t>(j) * n + i);
        ASSERT_TRUE(isFinite(e));
        if (!t.valid) continue;
        held += e.x * map0.frustum().texelSolidAngle(i, j) * t.distance * t.distance / t.cosine;
      }
    }
    EXPECT_NEAR(held, map0.stats().splattedFlux, 1e-3 * held);
    EXPECT_LE(held, map0.stats().emittedFlux * (1.0 + 1e-4));
    for (size_t k = 0; k < map.texelCount(); ++k) ASSERT_TRUE(isFinite(map.texelIrradiance(k)));
  }
}

// The flux reaching each ring 0.1 wide around the point under the ball centre, from lookups on a
// fine grid of the floor; the photon reference sums photon powers in the same rings.
constexpr int kRings = 24;
constexpr float kRingWidth = 0.1f;

std::vector<double> mapRingFlux(const CausticMapEstimator& maps) {
  std::vector<double> flux(kRings, 0.0);
  constexpr float kStep = 0.01f;
  const float extent = kRings * kRingWidth;
  for (float z = -extent + 0.5f * kStep; z < extent; z += kStep) {
    for (float x = -extent + 0.5f * kStep; x < extent; x += kStep) {
      const int ring = static_cast<int>(std::sqrt(x * x + z * z) / kRingWidth);
      if (ring >= kRings) continue;
      flux[ring] += maps.irradiance({x, 0.0f, z}, {0, 1, 0}).x * kStep * kStep;
    }
  }
  return flux;
}

std::vector<double> photonRingFlux(const Scene& scene, uint64_t photons) {
  const PhotonTracer tracer(scene, photons, 16);
  std::vector<double> flux(kRings, 0.0);
  for (const Photon& p : tracePhotons(tracer, 0, 0, photons, 0)) {
    if (std::abs(p.position.y) > 1e-3f) continue;
    const int ring = static_cast<int>(glm::length(Vec2(p.position.x, p.position.z)) / kRingWidth);
    if (ring < kRings) flux[ring] += p.power.x;
  }
  return flux;
}

double relativeError(const std::vector<double>& a, const std::vector<double>& reference) {
  double diff = 0.0, sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    diff += std::abs(a[i] - reference[i]);
    sum += reference[i];
  }
  return diff / sum;
}

TEST(CausticMap, ErrorAgainstPhotonMappingFallsAsResolutionRises) {
  SceneDescription d =
      loadScene(std::string(PRISM_SOURCE_DIR) + "/scenes/caustic-glass-sphere.yaml");
  d.caustics.method = CausticMethod::CausticMap;
  const std::vector<double> reference = photonRingFlux(Scene(d), 2'000'000);
  std::vector<double> errors;
  for (const int resolution : {64, 128, 256, 512}) {
    d.caustics.mapResolution = resolution;
    const Scene scene(d);
    const CausticMapEstimator maps(scene, 0);
    errors.push_back(relativeError(mapRingFlux(maps), reference));
    std::printf("resolution %4d: ring-flux error %.4f\n", resolution, errors.back());
  }
  EXPECT_LT(errors[3], errors[0]);
  EXPECT_LT(errors[2], errors[0]);
  EXPECT_LT(errors[3], 0.1);
}

// Lookups outside litBounds() return 0 without projecting, so the box must hold every point that
// can read a lit texel: points within a texel of its centre at its receiver's distance.
TEST(CausticMap, EveryPointThatCanReadALitTexelIsInsideTheLitBounds) {
  const Scene scene(sphereScene(1.5f, 64, 2));
  const CausticMap map(scene, 0, scene.causticSettings(), 0);
  const Aabb& lit = map.litBounds();
  const LightFrustum& frustum = map.frustum();
  const Vec3 light = scene.lights()[0].position;
  const int n = frustum.resolution();
  const float texelSize = 2.0f * frustum.views()[0].tanHalf / static_cast<float>(n);
  const auto inside = [&](const Vec3& p) {
    return glm::all(glm::greaterThanEqual(p, lit.lower)) &&
           glm::all(glm::lessThanEqual(p, lit.upper));
  };
  size_t litTexels = 0;
  for (int view = 0; view < static_cast<int>(frustum.views().size()); ++view) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const ReceiverTexel& t = map.receivers().at(view, i, j);
        const Color& e = map.texelIrradiance((static_cast<size_t>(view) * n + j) * n + i);
        if (!t.valid || maxComponent(e) <= 0.0f) continue;
        ++litTexels;
        // A lookup reads this texel from anywhere in [i - 0.5, i + 1.5) × [j - 0.5, j + 1.5),
        // within the depth tolerance of its receiver's distance.
        const float tolerance = 0.999f * CausticMap::depthTolerance(t, texelSize);
        for (const float x : {i - 0.5f, i + 0.5f, i + 1.499f}) {
          for (const float y : {j - 0.5f, j + 0.5f, j + 1.499f}) {
            for (const float r : {t.distance - tolerance, t.distance, t.distance + tolerance}) {
              const Vec3 p = light + r * frustum.direction(view, x, y);
              ASSERT_TRUE(inside(p)) << "texel " << i << ", " << j << " at " << x << ", " << y;
            }
          }
        }
      }
    }
  }
  EXPECT_GT(litTexels, 100u);
  // Light through the ball lands on the floor under it, in the light's view of the ball, and on
  // nothing else: the box is that thin slab of floor.
  EXPECT_TRUE(inside({0.0f, 0.0f, 0.0f}));
  EXPECT_FALSE(inside({0.0f, 0.0f, 3.0f}));  // past the light's view of the ball (tan 0.6 · 4)
  EXPECT_FALSE(inside({0.0f, 1.0f, 0.0f}));  // inside the ball, far above the floor
}

// irradiance() reads the four texels around a point as vector lanes; it must give what the
// bilinear shadow-map lookup gives written out corner by corner with glm, bit for bit: with one
// view and with six (a caster above the light as well as below it), at points on lit receivers,
// beside them, and anywhere around the lit box, under random normals.
struct ReferenceTexel {
  Vec3 normal{0.0f};
  float distance = 0.0f, tolerance = 0.0f;
  Color irradiance{0.0f};
};

ReferenceTexel referenceTexel(const CausticMap& map, int view, int i, int j) {
  const LightFrustum& frustum = map.frustum();
  const int n = frustum.resolution();
  const ReceiverTexel& t = map.receivers().at(view, i, j);
  ReferenceTexel r;
  r.irradiance = map.texelIrradiance((static_cast<size_t>(view) * n + j) * n + i);
  if (!t.valid) return r;
  r.normal = t.normal;
  r.distance = t.distance;
  r.tolerance = CausticMap::depthTolerance(t, 2.0f * frustum.views()[0].tanHalf / n);
  return r;
}

std::optional<LightSpacePoint> referenceProject(const LightFrustum& frustum, const Vec3& p) {
  const Vec3 d = p - frustum.light();
  const float dist = glm::length(d);
  if (!(dist > 0.0f)) return std::nullopt;
  const float n = static_cast<float>(frustum.resolution());
  for (size_t k = 0; k < frustum.views().size(); ++k) {
    const LightView& v = frustum.views()[k];
    const float z = glm::dot(d, v.axis);
    if (!(z > 0.0f)) continue;
    const float u = glm::dot(d, v.right) / z, w = glm::dot(d, v.up) / z;
    if (std::abs(u) > v.tanHalf || std::abs(w) > v.tanHalf) continue;
    const float scale = n / (2.0f * v.tanHalf);
    return LightSpacePoint{static_cast<int>(k),
                           std::clamp((u + v.tanHalf) * scale, 0.0f, n - 1e-3f),
                           std::clamp((w + v.tanHalf) * scale, 0.0f, n - 1e-3f), dist};
  }
  return std::nullopt;
}

Color referenceIrradiance(const CausticMap& map, const Vec3& position, const Vec3& normal) {
  const std::optional<LightSpacePoint> p = referenceProject(map.frustum(), position);
  if (!p) return Color(0.0f);
  const int n = map.frustum().resolution();
  const float fx = p->x - 0.5f, fy = p->y - 0.5f;
  const int i0 = static_cast<int>(std::floor(fx)), j0 = static_cast<int>(std::floor(fy));
  const float ax = fx - static_cast<float>(i0), ay = fy - static_cast<float>(j0);
  Color acc(0.0f);
  float wsum = 0.0f;
  for (int c = 0; c < 4; ++c) {
    const int i = std::clamp(i0 + (c & 1), 0, n - 1), j = std::clamp(j0 + (c >> 1), 0, n - 1);
    const ReferenceTexel t = referenceTexel(map, p->view, i, j);
    if (glm::dot(normal, t.normal) <= 0.0f || std::abs(t.distance - p->distance) > t.tolerance) {
      continue;
    }
    const float w = ((c & 1) ? ax : 1.0f - ax) * ((c >> 1) ? ay : 1.0f - ay);
    acc += w * t.irradiance;
    wsum += w;
  }
  return wsum > 1e-4f ? acc / wsum : Color(0.0f);
}

TEST(CausticMap, LookupIsTheBilinearShadowMapTestBitForBit) {
  SceneDescription above = sphereScene(1.5f, 48, 1);
  above.spheres.push_back({{0.3f, 6.5f, 0.2f}, 0.8f, 0, {}});  // casters all around: six views
  for (const bool cube : {false, true}) {
    const Scene scene(cube ? above : sphereScene(1.5f, 64, 2));
    const CausticMap map(scene, 0, scene.causticSettings(), 0);
    ASSERT_FALSE(map.empty());
    ASSERT_EQ(map.frustum().cube(), cube);
    const LightFrustum& frustum = map.frustum();
    const int n = frustum.resolution();
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    size_t compared = 0, lit = 0;
    std::vector<SurfaceHit> asked;  // every point again, for the lookups of several at once
    std::vector<Color> wanted;
    const auto compare = [&](const Vec3& position, const Vec3& normal) {
      const Color got = map.irradiance(position, normal);
      const Color want = referenceIrradiance(map, position, normal);
      ASSERT_EQ(std::memcmp(&got, &want, sizeof(Color)), 0)
          << "at " << position.x << ", " << position.y << ", " << position.z << ": " << got.x
          << " against " << want.x;
      ++compared;
      lit += maxComponent(got) > 0.0f ? 1 : 0;
      asked.push_back({});
      asked.back().position = position;
      asked.back().geometricNormal = normal;
      wanted.push_back(want);
    };
    // Points on and around every receiver texel the light sees, lit or not.
    for (int view = 0; view < static_cast<int>(frustum.views().size()); ++view) {
      for (int j = 0; j < n; j += 3) {
        for (int i = 0; i < n; i += 3) {
          const ReceiverTexel& t = map.receivers().at(view, i, j);
          if (!t.valid) continue;
          const float x = i + 0.5f + 0.9f * unit(random), y = j + 0.5f + 0.9f * unit(random);
          const float r = t.distance * (1.0f + 0.004f * unit(random));
          const Vec3 position = frustum.light() + r * frustum.direction(view, x, y);
          compare(position, t.normal);
          compare(position,
                  glm::normalize(t.normal + 0.8f * Vec3(unit(random), unit(random), unit(random))));
        }
      }
    }
    // Anywhere around the lit box, facing anywhere.
    const Aabb& box = map.litBounds();
    const Vec3 centre = 0.5f * (box.lower + box.upper), half = box.upper - centre + 0.5f;
    for (int k = 0; k < 4000; ++k) {
      const Vec3 position = centre + half * Vec3(unit(random), unit(random), unit(random));
      compare(position, glm::normalize(Vec3(unit(random), unit(random), unit(random))));
    }
    EXPECT_GT(lit, compared / 20) << "too few points read a lit texel to test the blend";
    // addIrradiance, 1 to 8 points at a time (lanes of four and the points left over), adds
    // the same answers to the sums.
    for (size_t first = 0, batch = 1; first < asked.size(); first += batch, batch = batch % 8 + 1) {
      const int count = static_cast<int>(std::min(batch, asked.size() - first));
      const SurfaceHit* points[8];
      Color sums[8];
      for (int i = 0; i < count; ++i) {
        points[i] = &asked[first + static_cast<size_t>(i)];
        sums[i] = Color(0.0f);
      }
      map.addIrradiance(points, count, sums);
      for (int i = 0; i < count; ++i) {
        const Color want = Color(0.0f) + wanted[first + static_cast<size_t>(i)];
        ASSERT_EQ(std::memcmp(&sums[i], &want, sizeof(Color)), 0)
            << "point " << first + static_cast<size_t>(i) << ", asked " << count << " at once";
      }
    }
  }
}

// A packet's points ask for their caustics at once (irradianceAtEach, the reads of all points'
// texels overlapping); each answer must be the one irradianceAt gives alone, in batches longer
// than the eight points CausticMap takes at a time, with points that read nothing among them.
TEST(CausticMap, PointsAskedTogetherGetTheirOwnAnswers) {
  const Scene scene(sphereScene(1.5f, 64, 2));
  const CausticMapEstimator estimator(scene, 0);
  ASSERT_FALSE(estimator.empty());
  std::mt19937 random(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<SurfaceHit> hits(21);
  for (size_t i = 0; i < hits.size(); ++i) {
    // Floor points under the ball (lit), some far outside the caustic, some facing down.
    const float reach = i % 5 == 4 ? 6.0f : 1.2f;
    hits[i].position = {reach * unit(random), 0.0f, reach * unit(random)};
    hits[i].geometricNormal = i % 7 == 3 ? Vec3(0, -1, 0) : Vec3(0, 1, 0);
  }
  for (const int count : {1, 8, 21}) {
    std::vector<const SurfaceHit*> points;
    for (int i = 0; i < count; ++i) points.push_back(&hits[static_cast<size_t>(i)]);
    std::vector<Color> together(static_cast<size_t>(count));
    estimator.irradianceAtEach(points.data(), count, together.data());
    size_t lit = 0;
    for (int i = 0; i < count; ++i) {
      const Color alone = estimator.irradianceAt(*points[static_cast<size_t>(i)]);
      const Color& got = together[static_cast<size_t>(i)];
      ASSERT_EQ(std::memcmp(&got, &alone, sizeof(Color)), 0) << "point " << i << " of " << count;
      lit += maxComponent(alone) > 0.0f ? 1 : 0;
    }
    if (count == 21) {
      EXPECT_GE(lit, 8u) << "too few points under the caustic to test the batch";
    }
  }
}

TEST(CausticMap, IsTheSameForAnyThreadCount) {
  const Scene scene(sphereScene(1.5f, 128, 2));
  const CausticMap one(scene, 0, scene.causticSettings(), 1);
  const CausticMap two(scene, 0, scene.causticSettings(), 3);
  ASSERT_EQ(one.texelCount(), two.texelCount());
  for (size_t i = 0; i < one.texelCount(); ++i) {
    ASSERT_EQ(one.texelIrradiance(i), two.texelIrradiance(i)) << i;
  }
}

}  // namespace
}  // namespace prism

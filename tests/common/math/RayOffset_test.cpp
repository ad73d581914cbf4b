#include "math/RayOffset.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <optional>
#include <random>
#include <string>

#include "render/WhittedIntegrator.h"

namespace prism {
namespace {

// --- the offset itself ----------------------------------------------------------------------

TEST(RayOffset, TheOriginLeavesTheErrorBoxOnTheSideTheRayGoes) {
  // Random points, error boxes, normals and directions over many magnitudes: measured in double,
  // the origin is beyond every point of the box along the normal, on the ray's side.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), exponent(-6.0f, 6.0f);
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    const float magnitude = std::pow(10.0f, exponent(rng));
    const Vec3 p = magnitude * Vec3(unit(rng), unit(rng), unit(rng));
    const Vec3 error = gammaBound(7) * magnitude * glm::abs(Vec3(unit(rng), unit(rng), unit(rng)));
    const Vec3 n = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)));
    const Vec3 w = glm::normalize(Vec3(unit(rng), unit(rng), unit(rng)));
    if (!std::isfinite(n.x) || !std::isfinite(w.x)) continue;
    const Vec3 origin = leavingOrigin(p, n, leavingDistance(p, error, n), w);
    const double side = glm::dot(w, n) < 0.0f ? -1.0 : 1.0;
    double along = 0.0, reach = 0.0;
    for (int a = 0; a < 3; ++a) {
      along += side * static_cast<double>(n[a]) * (static_cast<double>(origin[a]) - p[a]);
      reach += std::fabs(static_cast<double>(n[a])) * error[a];
    }
    ASSERT_GT(along, reach) << "p " << p.x << " " << p.y << " " << p.z << " error " << error.x;
    ++checked;
  }
  EXPECT_GT(checked, 190000);
}

TEST(RayOffset, AnExactPointStillMovesOffTheSurfaceButNeverToASubnormal) {
  // A point computed without error (the y = 0 floor) moves by the smallest normal float: the
  // surface's own test then puts the ray's start behind it.
  const Vec3 p(2.0f, 0.0f, -1.0f), up(0.0f, 1.0f, 0.0f);
  const float distance = leavingDistance(p, Vec3(0.0f), up);
  EXPECT_EQ(distance, std::numeric_limits<float>::min());
  const Vec3 origin = leavingOrigin(p, up, distance, glm::normalize(Vec3(0.2f, 1.0f, 0.0f)));
  EXPECT_EQ(origin.y, std::numeric_limits<float>::min());
  EXPECT_EQ(origin.x, 2.0f);
  EXPECT_EQ(origin.z, -1.0f);
  const Vec3 below = leavingOrigin(p, up, distance, -up);
  EXPECT_EQ(below.y, -std::numeric_limits<float>::min());
}

// The error bounds take magnitudes with absComponents (std::fabs), which makes -0 into +0 where
// glm::abs kept it: the distance a ray leaves by must not see the difference. Every combination
// of signed zeros in the point, its error and the normal (with the other components zero or
// not) gives the same distance to the bit.
TEST(RayOffset, TheLeavingDistanceDoesNotSeeTheSignOfAZero) {
  const float values[] = {0.0f, -0.0f, 0.5f, -3.0f};
  int checked = 0;
  for (int code = 0; code < 4 * 4 * 4 * 4 * 4 * 4; ++code) {
    int rest = code;
    const auto next = [&] {
      const float v = values[rest % 4];
      rest /= 4;
      return v;
    };
    const Vec3 p(next(), next(), 2.0f), error(next(), next(), 0.0f), n(next(), next(), 0.0f);
    const auto flipZeros = [](Vec3 v) {
      for (int a = 0; a < 3; ++a) v[a] = v[a] == 0.0f ? -v[a] : v[a];
      return v;
    };
    const float distance = leavingDistance(p, error, n);
    for (const Vec3& q : {p, flipZeros(p)}) {
      for (const Vec3& e : {error, flipZeros(error)}) {
        for (const Vec3& m : {n, flipZeros(n)}) {
          const float other = leavingDistance(q, e, m);
          ASSERT_EQ(std::memcmp(&other, &distance, sizeof(float)), 0) << code;
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 4 * 4 * 4 * 4 * 4 * 4 * 8);
  EXPECT_FALSE(std::signbit(absComponents(Vec3(-0.0f)).x));
  EXPECT_EQ(absComponents(Vec3(-2.0f, 3.0f, -0.5f)), Vec3(2.0f, 3.0f, 0.5f));
}

TEST(RayOffset, AShadowRayStopsAMillionthShortOfTheLight) {
  EXPECT_LT(shadowRayLength(10.0f), 10.0f);
  EXPECT_GT(shadowRayLength(10.0f), 10.0f * (1.0f - 1e-5f));
}

// --- rays leaving surfaces at every scale -----------------------------------------------------
//
// Each kind of primitive is set up as a "floor" of size `scale` whose top point C faces a tilted
// direction n, placed ten sizes from the world origin (so both absolute and relative rounding
// matter), and shaded through the real integrator:
// - acne: a diffuse floor lit from above must be lit at every hit, and a half-silvered mirror
//   must reflect the background exactly once, for eye rays from 10 to 10⁴ sizes away;
// - leaks: a sheet floats 10⁻⁴ sizes above the floor (a rug, a sheet of paper), lit from above;
//   no floor point under it may be lit.

enum class FloorKind { Plane, Triangles, Sphere, Cylinder };

std::string kindName(FloorKind kind) {
  switch (kind) {
    case FloorKind::Plane:
      return "plane";
    case FloorKind::Triangles:
      return "triangles";
    case FloorKind::Sphere:
      return "sphere";
    case FloorKind::Cylinder:
      return "cylinder";
  }
  return "?";
}

struct Frame {
  Vec3 top;     // C, the floor's top point
  Vec3 normal;  // n, the floor's normal at C
  Vec3 across1, across2;
};

Frame floorFrame(float scale) {
  Frame f;
  f.top = scale * Vec3(10.0f, -3.0f, 7.0f);
  f.normal = glm::normalize(Vec3(0.3f, 1.0f, 0.2f));
  orthonormalBasis(f.normal, f.across1, f.across2);
  return f;
}

MeshDesc quad(const Vec3& centre, const Vec3& a, const Vec3& b, float halfSize, MaterialId m) {
  MeshDesc mesh;
  mesh.source = "quad";
  for (const float sa : {-1.0f, 1.0f}) {
    for (const float sb : {-1.0f, 1.0f}) {
      mesh.positions.push_back(centre + halfSize * (sa * a + sb * b));
    }
  }
  mesh.indices = {0, 1, 3, 0, 3, 2};  // the shared edge runs through the centre
  mesh.material = m;
  return mesh;
}

void addFloor(SceneDescription& d, FloorKind kind, const Frame& f, float scale, MaterialId m) {
  const float radius = 2.0f * scale;
  switch (kind) {
    case FloorKind::Plane:
      d.planes.push_back({f.top, f.normal, m, {}});
      break;
    case FloorKind::Triangles:
      d.meshes.push_back(quad(f.top, f.across1, f.across2, 4.0f * scale, m));
      break;
    case FloorKind::Sphere:
      d.spheres.push_back({f.top - radius * f.normal, radius, m, {}});
      break;
    case FloorKind::Cylinder: {
      const Vec3 axisPoint = f.top - radius * f.normal;
      ConeDesc c;
      c.base = axisPoint - 4.0f * scale * f.across1;
      c.apex = axisPoint + 4.0f * scale * f.across1;
      c.baseRadius = c.apexRadius = radius;
      c.material = m;
      d.cones.push_back(c);
      break;
    }
  }
}

struct Counts {
  int rays = 0;
  int hits = 0;
  int wrong = 0;
};

// Shoots `count` rays from origins drawn by `origin` at points near C and counts the hits whose
// radiance fails `expected`.
template <class Origin, class Check>
Counts shoot(const Scene& scene, const Frame& f, float scale, int count, Origin&& origin,
             Check&& check) {
  const WhittedIntegrator integrator(scene);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> spread(-0.1f, 0.1f);
  Counts counts;
  for (int i = 0; i < count; ++i) {
    const Vec3 target = f.top + scale * (spread(rng) * f.across1 + spread(rng) * f.across2);
    const Vec3 from = origin(rng, target);
    Ray ray{from, glm::normalize(target - from)};
    ++counts.rays;
    HitRecord hit;
    if (!scene.intersect(ray, hit)) continue;
    ++counts.hits;
    RayCounters rays;
    if (!check(integrator.radiance(ray, 0, Color(1.0f), rays))) ++counts.wrong;
  }
  return counts;
}

struct ScaleCase {
  FloorKind kind;
  TriangleTest test;
};

std::string caseName(const ScaleCase& c) {
  return kindName(c.kind) + (c.test == TriangleTest::Watertight ? "Watertight" : "");
}

class LeavingSurfaces : public testing::TestWithParam<ScaleCase> {};

// The case's floor of one material, and a point light if `light` is given.
SceneDescription floorScene(const ScaleCase& c, const Frame& f, float scale,
                            const MaterialDesc& material, std::optional<Vec3> light) {
  SceneDescription d;
  d.render.triangleTest = c.test;
  d.materials.push_back(material);
  addFloor(d, c.kind, f, scale, 0);
  if (light) {
    PointLightDesc l;
    l.position = *light;
    d.lights.push_back(l);
  }
  return d;
}

MaterialDesc whiteDiffuse() {
  MaterialDesc m;
  m.diffuse = Color(1.0f);
  return m;
}

constexpr float kScales[] = {1e-3f, 1.0f, 1e3f, 1e5f};

TEST_P(LeavingSurfaces, NoAcneForEyeRaysFromNearAndFar) {
  const FloorKind kind = GetParam().kind;
  for (const float scale : kScales) {
    const Frame f = floorFrame(scale);
    for (const float distance : {10.0f, 1e3f, 1e4f}) {
      // An eye on the lit side, `distance` sizes away, aiming at points near C.
      const auto eye = [&](std::mt19937& rng, const Vec3& target) {
        std::uniform_real_distribution<float> tilt(-0.6f, 0.6f);
        const Vec3 from = f.normal + tilt(rng) * f.across1 + tilt(rng) * f.across2;
        return target + distance * scale * glm::normalize(from);
      };
      {  // Shadow rays: lit from above, every hit must receive light.
        const Scene scene(
            floorScene(GetParam(), f, scale, whiteDiffuse(),
                       f.top + 3.0f * scale * glm::normalize(f.normal + 0.5f * f.across1)));
        const Counts c =
            shoot(scene, f, scale, 2000, eye, [](const Color& L) { return L.x > 0.0f; });
        std::printf("acne  %-20s scale %-6g eye %-6g sizes: %4d of %4d shadow rays blocked\n",
                    caseName(GetParam()).c_str(), scale, distance, c.wrong, c.hits);
        // Möller–Trumbore lets a ray through the quad's shared edge now and then (stability.md).
        EXPECT_GE(c.hits, c.rays * 99 / 100);
        EXPECT_EQ(c.wrong, 0) << kindName(kind) << " scale " << scale << " eye at " << distance
                              << " sizes: " << c.wrong << " of " << c.hits << " hits self-shadowed";
      }
      {  // Reflected rays: a half mirror under a uniform sky reflects it once, exactly.
        MaterialDesc mirror;
        mirror.diffuse = Color(0.0f);
        mirror.reflectance = Color(0.5f);
        SceneDescription d = floorScene(GetParam(), f, scale, mirror, std::nullopt);
        d.background = Color(1.0f);
        const Scene scene(d);
        const Counts c =
            shoot(scene, f, scale, 2000, eye, [](const Color& L) { return L.x == 0.5f; });
        std::printf("acne  %-20s scale %-6g eye %-6g sizes: %4d of %4d reflections hit it again\n",
                    caseName(GetParam()).c_str(), scale, distance, c.wrong, c.hits);
        EXPECT_EQ(c.wrong, 0) << kindName(kind) << " scale " << scale << " eye at " << distance
                              << " sizes: " << c.wrong << " of " << c.hits
                              << " reflections met their own surface";
      }
    }
  }
}

TEST_P(LeavingSurfaces, NoLightLeaksUnderASheetCloseAboveTheSurface) {
  const FloorKind kind = GetParam().kind;
  for (const float scale : kScales) {
    const Frame f = floorFrame(scale);
    const float gap = 1e-4f * scale;
    SceneDescription d =
        floorScene(GetParam(), f, scale, whiteDiffuse(), f.top + 3.0f * scale * f.normal);
    d.meshes.push_back(quad(f.top + gap * f.normal, f.across1, f.across2, 0.5f * scale, 0));
    const Scene scene(d);
    // Eyes inside the gap, looking down at the floor under the sheet.
    const auto insideGap = [&](std::mt19937& rng, const Vec3& target) {
      std::uniform_real_distribution<float> side(-1.0f, 1.0f);
      const Vec3 away = glm::normalize(f.normal + side(rng) * f.across1 + side(rng) * f.across2);
      // Start halfway up the gap above the target's foot on the floor.
      return target + 0.5f * gap * away / glm::dot(away, f.normal);
    };
    const Counts c =
        shoot(scene, f, scale, 4000, insideGap, [](const Color& L) { return L.x == 0.0f; });
    std::printf("leak  %-20s scale %-6g: %4d of %4d floor points under the sheet lit\n",
                caseName(GetParam()).c_str(), scale, c.wrong, c.hits);
    EXPECT_GT(c.hits, c.rays * 9 / 10);
    EXPECT_EQ(c.wrong, 0) << kindName(kind) << " scale " << scale << ": " << c.wrong << " of "
                          << c.hits << " floor points under the sheet are lit";
  }
}

TEST(LeavingSurfaces, ALightSetIntoASurfaceIsNotShadowedByIt) {
  // A bulb set into a tilted ceiling (plane, or two triangles) above a floor: the floor is lit.
  for (const float scale : kScales) {
    for (const bool triangles : {false, true}) {
      const Frame f = floorFrame(scale);
      SceneDescription d;
      d.materials.push_back(whiteDiffuse());
      d.planes.push_back({f.top, f.normal, 0, {}});
      const Vec3 ceilingPoint = f.top + 2.0f * scale * f.normal;
      const Vec3 tilted = glm::normalize(f.normal + 0.4f * f.across2);
      Vec3 ceilingA, ceilingB;
      orthonormalBasis(tilted, ceilingA, ceilingB);
      if (triangles) {
        d.meshes.push_back(quad(ceilingPoint, ceilingA, ceilingB, 4.0f * scale, 0));
      } else {
        d.planes.push_back({ceilingPoint, tilted, 0, {}});
      }
      PointLightDesc light;
      light.position = ceilingPoint + 0.3f * scale * ceilingA;  // on the ceiling, up to rounding
      d.lights.push_back(light);
      const Scene scene(d);
      const auto below = [&](std::mt19937& rng, const Vec3& target) {
        std::uniform_real_distribution<float> tilt(-0.5f, 0.5f);
        return target + scale * (f.normal + tilt(rng) * f.across1 + tilt(rng) * f.across2);
      };
      const Counts c =
          shoot(scene, f, scale, 2000, below, [](const Color& L) { return L.x > 0.0f; });
      EXPECT_EQ(c.hits, c.rays);
      EXPECT_EQ(c.wrong, 0) << (triangles ? "triangles" : "plane") << " scale " << scale << ": "
                            << c.wrong << " of " << c.hits << " floor points in the dark";
    }
  }
}

TEST(LeavingSurfaces, OverlappingSpheresDoNotShadowEachOtherWhereTheyMeet) {
  // A row of 100 spheres of radius s, each 0.01 s along from the last (SPD's shells is a spiral of
  // such spheres): where two meet their surfaces cross at a shallow angle, and which of them an
  // eye ray meets first is decided within the rounding of its distance. The point taken, on
  // the one that won, may then lie a rounding inside the other, and a ray leaving it hits that
  // sphere at once. Lit from far above, every point facing the light must be lit.
  for (const float scale : kScales) {
    const Vec3 first = scale * Vec3(10.0f, -3.0f, 7.0f);
    SceneDescription d;
    d.materials.push_back(whiteDiffuse());
    for (int i = 0; i < 100; ++i) {
      d.spheres.push_back({first + Vec3(0.01f * scale * float(i), 0.0f, 0.0f), scale, 0, {}});
    }
    const Vec3 middle = first + Vec3(0.5f * scale, 0.0f, 0.0f);
    PointLightDesc light;
    light.position = middle + 1e3f * scale * glm::normalize(Vec3(0.1f, -0.2f, 1.0f));
    d.lights.push_back(light);
    const Scene scene(d);
    const WhittedIntegrator integrator(scene);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> along(0.0f, 1.0f), across(-0.6f, 0.6f);
    for (const float distance : {70.0f, 1e3f, 1e4f}) {
      const Vec3 eye = middle + distance * scale * glm::normalize(Vec3(0.2f, -1.0f, 1.0f));
      int facing = 0, dark = 0;
      for (int i = 0; i < 4000; ++i) {
        const Vec3 target = first + scale * Vec3(along(rng), across(rng), 1.0f);
        const Ray ray{eye, glm::normalize(target - eye)};
        HitRecord hit;
        if (!scene.intersect(ray, hit)) continue;
        const SurfaceHit s = scene.surface(ray, hit);
        // Well inside the lit side: no sphere of the row can shadow it.
        if (glm::dot(s.geometricNormal, glm::normalize(light.position - s.position)) < 0.5f) {
          continue;
        }
        ++facing;
        RayCounters rays;
        if (!(integrator.radiance(ray, 0, Color(1.0f), rays).x > 0.0f)) ++dark;
      }
      std::printf("seams  scale %-6g eye %-6g sizes: %4d of %4d lit points in the dark\n", scale,
                  distance, dark, facing);
      EXPECT_GT(facing, 2000);
      EXPECT_EQ(dark, 0) << "scale " << scale << ", eye " << distance << " sizes away: " << dark
                         << " of " << facing << " points facing the light are dark";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    EveryKind, LeavingSurfaces,
    testing::Values(ScaleCase{FloorKind::Plane, TriangleTest::MollerTrumbore},
                    ScaleCase{FloorKind::Triangles, TriangleTest::MollerTrumbore},
                    ScaleCase{FloorKind::Triangles, TriangleTest::Watertight},
                    ScaleCase{FloorKind::Sphere, TriangleTest::MollerTrumbore},
                    ScaleCase{FloorKind::Cylinder, TriangleTest::MollerTrumbore}),
    [](const testing::TestParamInfo<ScaleCase>& info) { return caseName(info.param); });

}  // namespace
}  // namespace prism

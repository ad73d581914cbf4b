// Rays per CPU-second: Prism's traversal against Intel Embree 3 on the same triangles and the
// same rays, side by side in one process (docs/performance.md, "Rays against Embree").
//
//   build/tests/prism_embree_compare [--runs N] [--quick] [--no-variants] [--threads 1,2]
//                                    [--kinds primary,incoherent,shadow] [--no-generated]
//                                    [--build-only] [--embree-config CFG] [mesh.obj ...]
//
// Meshes: a subdivided sphere and a displaced grid generated here, plus any OBJ named. Rays:
// coherent primary rays from a camera (1024 × 768, in 4 × 4 pixel tiles), incoherent rays
// (diffuse bounces from the primary hits, shuffled), and shadow rays from the primary hits
// towards a light. Prism runs its renderer's own Scene::intersect / Scene::occluded in each
// traversal mode (--no-variants leaves out the intermediate ones), and Scene::intersect8 /
// occluded8 on packets of eight consecutive rays; Embree runs single rays
// (rtcIntersect1/rtcOccluded1) and 16-ray packets (rtcIntersect16/rtcOccluded16, which its AVX-512
// path prefers here). Times are CPU seconds of the tracing threads (CLOCK_THREAD_CPUTIME_ID), and
// every number is the median of
// --runs rounds in which all contenders run one after another, in a rotating order.
// --build-only stops after the build and memory lines (many rounds of the build in seconds).
// --embree-config passes its string to rtcNewDevice: "isa=sse2" holds Embree to the instruction
// set of Prism's default build (Embree otherwise picks the widest the CPU has, AVX2 or AVX-512).
#include <embree3/rtcore.h>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "math/Random.h"
#include "math/Simd.h"
#include "parse/ObjLoader.h"
#include "scene/Scene.h"
#include "tests/common/geometry/TestMeshes.h"

namespace prism {
namespace {

double threadCpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double wallSeconds() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double processCpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// ---- meshes ---------------------------------------------------------------------------------

MeshDesc subdividedSphere(int levels) {
  test::TestMesh sphere = test::icosphere(levels, Vec3(0.0f), 1.0f);
  MeshDesc mesh;
  mesh.source = "sphere-l" + std::to_string(levels);
  mesh.positions = std::move(sphere.positions);
  mesh.indices = std::move(sphere.indices);
  return mesh;
}

// A height field of n × n quads, displaced by a few octaves of waves.
MeshDesc displacedGrid(int n) {
  MeshDesc mesh;
  mesh.source = "grid-" + std::to_string(n);
  for (int z = 0; z <= n; ++z) {
    for (int x = 0; x <= n; ++x) {
      const float u = 2.0f * x / n - 1.0f, w = 2.0f * z / n - 1.0f;
      float h = 0.0f, amplitude = 0.15f, frequency = 3.0f;
      for (int octave = 0; octave < 5; ++octave) {
        h += amplitude * std::sin(frequency * u + octave) * std::cos(frequency * 1.3f * w);
        amplitude *= 0.5f;
        frequency *= 2.1f;
      }
      mesh.positions.push_back({u, h, w});
    }
  }
  for (int z = 0; z < n; ++z) {
    for (int x = 0; x < n; ++x) {
      const uint32_t i = z * (n + 1) + x;
      mesh.indices.insert(mesh.indices.end(), {i, i + 1, i + n + 1, i + 1, i + n + 2, i + n + 1});
    }
  }
  return mesh;
}

// ---- rays -----------------------------------------------------------------------------------

struct RaySet {
  std::string kind;  // primary, incoherent, shadow
  std::vector<Ray> rays;
  int tileWidth = 0;  // primary/shadow: rays are ordered in 4×4 pixel tiles for packets
};

Aabb meshBounds(const MeshDesc& mesh) {
  Aabb b;
  for (const Vec3& p : mesh.positions) b.extend(p);
  return b;
}

// A camera looking at the mesh from the front and above, rays in 4×4 pixel tiles.
std::vector<Ray> primaryRays(const Aabb& bounds, int width, int height) {
  const Vec3 center = bounds.center();
  const float radius = 0.5f * glm::length(bounds.extent());
  const Vec3 eye = center + radius * Vec3(0.6f, 1.1f, 2.2f);
  const Vec3 forward = glm::normalize(center - eye);
  const Vec3 right = glm::normalize(glm::cross(forward, Vec3(0, 1, 0)));
  const Vec3 up = glm::cross(right, forward);
  const float halfHeight = std::tan(0.5f * 40.0f * 3.14159265f / 180.0f);
  const float halfWidth = halfHeight * width / height;
  std::vector<Ray> rays;
  for (int ty = 0; ty < height; ty += 4) {
    for (int tx = 0; tx < width; tx += 4) {
      for (int y = ty; y < ty + 4; ++y) {
        for (int x = tx; x < tx + 4; ++x) {
          const float sx = (2.0f * (x + 0.5f) / width - 1.0f) * halfWidth;
          const float sy = (1.0f - 2.0f * (y + 0.5f) / height) * halfHeight;
          rays.push_back({eye, glm::normalize(forward + sx * right + sy * up)});
        }
      }
    }
  }
  return rays;
}

// Diffuse bounces: from each primary hit, a direction uniform over the hemisphere around the
// surface normal, the rays shuffled so that neighbours share nothing. A primary miss gives a
// ray with an empty interval, which every tracer skips.
std::vector<Ray> incoherentRays(const Scene& scene, const std::vector<Ray>& primary,
                                uint64_t seed) {
  Pcg32 rng(seed, 2);
  std::vector<Ray> rays;
  for (const Ray& p : primary) {
    HitRecord hit;
    Ray r{p.origin, p.direction, 0.0f, -1.0f};
    if (scene.intersect(p, hit)) {
      const SurfaceHit s = scene.surface(p, hit);
      const float z = 2.0f * rng.nextFloat() - 1.0f, phi = 6.2831853f * rng.nextFloat();
      const float radius = std::sqrt(std::max(0.0f, 1.0f - z * z));
      Vec3 d(radius * std::cos(phi), radius * std::sin(phi), z);
      if (glm::dot(d, s.geometricNormal) < 0.0f) d = -d;
      r = {s.rayOrigin(d), d};
    }
    rays.push_back(r);
  }
  for (size_t i = rays.size(); i > 1; --i) std::swap(rays[i - 1], rays[rng.nextUint() % i]);
  return rays;
}

// From each primary hit towards a light above and to the side; a primary miss gives a ray
// with an empty interval, which both tracers skip (it keeps the packets' tiles intact).
std::vector<Ray> shadowRays(const Scene& scene, const std::vector<Ray>& primary,
                            const Aabb& bounds) {
  const float radius = 0.5f * glm::length(bounds.extent());
  const Vec3 light = bounds.center() + radius * Vec3(-1.5f, 2.5f, 1.0f);
  std::vector<Ray> rays;
  for (const Ray& p : primary) {
    HitRecord hit;
    Ray r{p.origin, p.direction, 0.0f, -1.0f};  // empty: tMax < tMin
    if (scene.intersect(p, hit)) {
      const SurfaceHit s = scene.surface(p, hit);
      const Vec3 toLight = light - s.position;
      const float distance = glm::length(toLight);
      r.direction = toLight / distance;
      r.origin = s.rayOrigin(r.direction);
      r.tMax = distance;
    }
    rays.push_back(r);
  }
  return rays;
}

// ---- Embree ---------------------------------------------------------------------------------

std::atomic<ssize_t> embreeBytes{0};

bool countEmbreeMemory(void*, ssize_t bytes, bool) {
  embreeBytes += bytes;
  return true;
}

struct EmbreeScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  double buildSeconds = 0.0;
  double buildCpuSeconds = 0.0;  // every thread of the process, Embree's workers included
  size_t bytes = 0;

  EmbreeScene(const MeshDesc& mesh, const std::string& config) {
    // Builds on every core, as Prism's does.
    device = rtcNewDevice(config.empty() ? nullptr : config.c_str());
    if (device == nullptr) throw std::runtime_error("Embree refused the device config: " + config);
    rtcSetDeviceMemoryMonitorFunction(device, countEmbreeMemory, nullptr);
    const ssize_t before = embreeBytes;
    scene = rtcNewScene(device);
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.positions.size()));
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      std::memcpy(vertices + 3 * i, &mesh.positions[i], 3 * sizeof(float));
    }
    auto* indices = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(uint32_t), mesh.triangleCount()));
    std::memcpy(indices, mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
    const double start = wallSeconds(), startCpu = processCpuSeconds();
    rtcCommitScene(scene);
    buildSeconds = wallSeconds() - start;
    buildCpuSeconds = processCpuSeconds() - startCpu;
    bytes = static_cast<size_t>(embreeBytes - before);
  }
  ~EmbreeScene() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
};

RTCRayHit toEmbree(const Ray& r) {
  RTCRayHit rh{};
  rh.ray.org_x = r.origin.x;
  rh.ray.org_y = r.origin.y;
  rh.ray.org_z = r.origin.z;
  rh.ray.dir_x = r.direction.x;
  rh.ray.dir_y = r.direction.y;
  rh.ray.dir_z = r.direction.z;
  rh.ray.tnear = r.tMin;
  rh.ray.tfar = r.tMax;
  rh.ray.mask = ~0u;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

template <class Packet>
void fillPacket(Packet& p, int valid[16], const Ray* rays, int count) {
  for (int i = 0; i < 16; ++i) {
    const bool live = i < count && rays[i].tMax >= rays[i].tMin;
    valid[i] = live ? -1 : 0;
    const Ray& r = rays[std::min(i, count - 1)];
    auto& ray = [&]() -> RTCRay16& {
      if constexpr (std::is_same_v<Packet, RTCRayHit16>) {
        return p.ray;
      } else {
        return p;
      }
    }();
    ray.org_x[i] = r.origin.x;
    ray.org_y[i] = r.origin.y;
    ray.org_z[i] = r.origin.z;
    ray.dir_x[i] = r.direction.x;
    ray.dir_y[i] = r.direction.y;
    ray.dir_z[i] = r.direction.z;
    ray.tnear[i] = r.tMin;
    ray.tfar[i] = r.tMax;
    ray.mask[i] = ~0u;
    ray.time[i] = 0.0f;
    ray.flags[i] = 0;
    if constexpr (std::is_same_v<Packet, RTCRayHit16>) p.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
  }
}

// ---- the contest ----------------------------------------------------------------------------

// Traces rays[begin, end) and returns how many hit, so no tracer's work can be optimised away.
using Tracer = std::function<size_t(const std::vector<Ray>&, size_t, size_t)>;

struct Contender {
  std::string name;
  Tracer trace;
  std::vector<double> mraysPerCpuSecond;  // one per round
  std::vector<double> mraysPerWallSecond;
};

// Runs one contender over the ray set on `threads` threads; returns (CPU-seconds, wall seconds).
std::pair<double, double> runOnce(const Tracer& trace, const std::vector<Ray>& rays, int threads,
                                  size_t& hits) {
  std::vector<double> cpu(threads, 0.0);
  std::vector<size_t> hitCounts(threads, 0);
  const double wallStart = wallSeconds();
  // Threads take 4096-ray chunks in turn, so both see coherent runs.
  std::atomic<size_t> next{0};
  const size_t chunk = 4096;
  auto work = [&](int t) {
    const double start = threadCpuSeconds();
    for (;;) {
      const size_t begin = next.fetch_add(chunk);
      if (begin >= rays.size()) break;
      hitCounts[t] += trace(rays, begin, std::min(rays.size(), begin + chunk));
    }
    cpu[t] = threadCpuSeconds() - start;
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& th : pool) th.join();
  const double wall = wallSeconds() - wallStart;
  hits = 0;
  double cpuTotal = 0.0;
  for (int t = 0; t < threads; ++t) {
    hits += hitCounts[t];
    cpuTotal += cpu[t];
  }
  return {cpuTotal, wall};
}

struct Options {
  int runs = 7;
  bool quick = false;
  std::vector<int> threads = {1, 2};
  std::vector<std::string> objs;
  bool withVariants = true;  // also time the intermediate Prism traversals
  bool buildOnly = false;    // only the build and memory lines
  std::string embreeConfig;  // rtcNewDevice's configuration string, e.g. "isa=sse2"
  std::vector<std::string> kinds = {"primary", "incoherent", "shadow"};  // ray sets timed
  bool generatedMeshes = true;  // the subdivided sphere and displaced grid besides any OBJ
};

struct Agreement {
  size_t rays = 0, hitMismatch = 0, primitiveMismatch = 0, primitiveTies = 0;
  double maxRelativeTError = 0.0;
};

// Prism's wide walk against Embree's single rays, ray by ray.
Agreement compareHits(const Scene& scene, RTCScene embree, const RaySet& set) {
  Agreement a;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (const Ray& r : set.rays) {
    if (r.tMax < r.tMin) continue;
    ++a.rays;
    if (set.kind == "shadow") {
      RTCRayHit rh = toEmbree(r);
      rtcOccluded1(embree, &context, &rh.ray);
      const bool embreeBlocked = rh.ray.tfar < 0.0f;
      if (embreeBlocked != scene.occluded(r)) ++a.hitMismatch;
      continue;
    }
    HitRecord hit;
    const bool prismHit = scene.intersect(r, hit);
    RTCRayHit rh = toEmbree(r);
    rtcIntersect1(embree, &context, &rh);
    const bool embreeHit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    if (prismHit != embreeHit) {
      ++a.hitMismatch;
      continue;
    }
    if (!prismHit) continue;
    const double rel = std::abs(hit.t - rh.ray.tfar) / std::max(1e-6f, rh.ray.tfar);
    a.maxRelativeTError = std::max(a.maxRelativeTError, rel);
    if (scene.meshFace(hit) != rh.hit.primID) {
      ++a.primitiveMismatch;
      if (rel < 1e-5) ++a.primitiveTies;  // the same point: a shared edge or vertex
    }
  }
  return a;
}

void benchmarkMesh(const MeshDesc& mesh, const Options& options) {
  SceneDescription d;
  d.meshes.push_back(mesh);
  std::printf("\n## %s: %zu triangles\n\n", mesh.source.c_str(), mesh.triangleCount());

  // Builds alternate, Prism then Embree, --runs times; the last of each is kept for tracing.
  std::vector<double> prismBuilds, prismBvh, prismCollapse, embreeBuilds, prismCpu, embreeCpu;
  std::unique_ptr<Scene> prismScene;
  std::unique_ptr<EmbreeScene> embreeScene;
  for (int round = 0; round < options.runs; ++round) {
    prismScene.reset();
    const double start = wallSeconds(), startCpu = processCpuSeconds();
    prismScene = std::make_unique<Scene>(d, Traversal::WideSimd);
    prismBuilds.push_back(wallSeconds() - start);
    prismCpu.push_back(processCpuSeconds() - startCpu);
    prismBvh.push_back(prismScene->buildStats().bvh.seconds);
    prismCollapse.push_back(prismScene->buildStats().wideBvh.seconds);
    embreeScene.reset();
    embreeScene = std::make_unique<EmbreeScene>(mesh, options.embreeConfig);
    embreeCpu.push_back(embreeScene->buildCpuSeconds);
    embreeBuilds.push_back(embreeScene->buildSeconds);
  }
  const Scene& prism = *prismScene;
  const EmbreeScene& embree = *embreeScene;
  const SceneBuildStats& st = prism.buildStats();
  std::printf(
      "build (wall ms, all cores, median of %d alternating): Prism scene %.2f (binary SAH %.2f, "
      "collapse %.2f), Embree %.2f, Prism/Embree %.2f; CPU ms of all threads: Prism %.2f, Embree "
      "%.2f, Prism/Embree %.2f\n",
      options.runs, 1e3 * median(prismBuilds), 1e3 * median(prismBvh), 1e3 * median(prismCollapse),
      1e3 * median(embreeBuilds), median(prismBuilds) / median(embreeBuilds),
      1e3 * median(prismCpu), 1e3 * median(embreeCpu), median(prismCpu) / median(embreeCpu));
  std::printf(
      "memory held (MiB): Prism %.1f (binary nodes+order %.1f, wide nodes %.1f, packs %.1f, "
      "shading and other geometry %.1f), Embree %.1f, Prism/Embree %.2f\n",
      st.heldBytes() / 1048576.0, (st.binaryBvhReleased ? 0 : st.bvh.memoryBytes) / 1048576.0,
      st.wideBvh.memoryBytes / 1048576.0, st.packBytes / 1048576.0, st.geometryBytes / 1048576.0,
      embree.bytes / 1048576.0, static_cast<double>(st.heldBytes()) / embree.bytes);
  if (options.buildOnly) return;

  SceneDescription watertightDescription = d;
  watertightDescription.render.triangleTest = TriangleTest::Watertight;
  const Scene prismWatertight(watertightDescription, Traversal::WideSimd);
  const Scene prismLeaves(d, Traversal::WideScalarLeaves);
  const Scene prismBinary(d, Traversal::BinaryScalar);
  // The baseline's kernels (x86-64, SSE2), beside the best set this CPU runs, chosen at run time.
  Scene prismBaseline(d, Traversal::WideSimd);
  prismBaseline.useInstructionSet(InstructionSet::Baseline);
  const bool baselineApart = prism.instructionSet() != InstructionSet::Baseline;
  const std::string chosen = std::string(" (") + instructionSetName(prism.instructionSet()) + ")";

  const Aabb bounds = meshBounds(mesh);
  const int width = options.quick ? 256 : 1024, height = options.quick ? 192 : 768;
  std::vector<RaySet> sets;
  sets.push_back({"primary", primaryRays(bounds, width, height), width});
  sets.push_back({"incoherent", incoherentRays(prism, sets[0].rays, 9), 0});
  sets.push_back({"shadow", shadowRays(prism, sets[0].rays, bounds), width});

  for (const Scene* scene : {&prism, &prismWatertight}) {
    for (const RaySet& set : sets) {
      const Agreement a = compareHits(*scene, embree.scene, set);
      std::printf(
          "agreement %-10s (%s): %zu rays, hit/miss differs %zu (%.4f%%), other triangle %zu "
          "(%zu of them at the same t), max relative t difference %.2g\n",
          set.kind.c_str(), scene == &prism ? "Moller-Trumbore" : "watertight", a.rays,
          a.hitMismatch, 100.0 * a.hitMismatch / a.rays, a.primitiveMismatch, a.primitiveTies,
          a.maxRelativeTError);
    }
  }

  for (const RaySet& set : sets) {
    if (std::find(options.kinds.begin(), options.kinds.end(), set.kind) == options.kinds.end()) {
      continue;
    }
    const bool shadow = set.kind == "shadow";
    std::vector<Contender> contenders;
    auto prismTracer = [shadow](const Scene& scene) -> Tracer {
      return [&scene, shadow](const std::vector<Ray>& rays, size_t b, size_t e) {
        size_t hits = 0;
        HitRecord hit;
        for (size_t i = b; i < e; ++i) {
          if (rays[i].tMax < rays[i].tMin) continue;
          hits += shadow ? scene.occluded(rays[i]) : scene.intersect(rays[i], hit);
        }
        return hits;
      };
    };
    contenders.push_back({"Prism wide+SIMD" + chosen, prismTracer(prism), {}, {}});
    if (baselineApart) {
      contenders.push_back({"Prism wide+SIMD (x86-64)", prismTracer(prismBaseline), {}, {}});
    }
    // Eight consecutive rays at a time: half a 4 × 4 pixel tile for primary and shadow rays.
    auto prismPackets = [shadow](const Scene& scene) -> Tracer {
      return [&scene, shadow](const std::vector<Ray>& rays, size_t b, size_t e) {
        size_t hits = 0;
        HitRecord hit[8];
        bool found[8];
        for (size_t i = b; i < e; i += 8) {
          const int n = static_cast<int>(std::min<size_t>(8, e - i));
          if (shadow) {
            scene.occluded8(&rays[i], n, found);
          } else {
            scene.intersect8(&rays[i], n, hit, found);
          }
          for (int k = 0; k < n; ++k) hits += found[k];
        }
        return hits;
      };
    };
    contenders.push_back({"Prism packet8" + chosen, prismPackets(prism), {}, {}});
    if (baselineApart) {
      contenders.push_back({"Prism packet8 (x86-64)", prismPackets(prismBaseline), {}, {}});
    }
    contenders.push_back({"Prism watertight", prismTracer(prismWatertight), {}, {}});
    if (options.withVariants) {
      contenders.push_back({"Prism wide, scalar tri", prismTracer(prismLeaves), {}, {}});
      contenders.push_back({"Prism binary (main)", prismTracer(prismBinary), {}, {}});
      if (shadow) {
        // Shadows answered by a closest-hit search: what the any-hit walk buys.
        contenders.push_back({"Prism wide, closest-hit",
                              [&](const std::vector<Ray>& rays, size_t b, size_t e) {
                                size_t hits = 0;
                                HitRecord hit;
                                for (size_t i = b; i < e; ++i) {
                                  if (rays[i].tMax < rays[i].tMin) continue;
                                  hits += prism.intersect(rays[i], hit);
                                }
                                return hits;
                              },
                              {},
                              {}});
      }
    }
    RTCScene es = embree.scene;
    contenders.push_back({"Embree single",
                          [es, shadow](const std::vector<Ray>& rays, size_t b, size_t e) {
                            RTCIntersectContext context;
                            rtcInitIntersectContext(&context);
                            size_t hits = 0;
                            for (size_t i = b; i < e; ++i) {
                              if (rays[i].tMax < rays[i].tMin) continue;
                              RTCRayHit rh = toEmbree(rays[i]);
                              if (shadow) {
                                rtcOccluded1(es, &context, &rh.ray);
                                hits += rh.ray.tfar < 0.0f;
                              } else {
                                rtcIntersect1(es, &context, &rh);
                                hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
                              }
                            }
                            return hits;
                          },
                          {},
                          {}});
    contenders.push_back({"Embree packet16",
                          [es, shadow](const std::vector<Ray>& rays, size_t b, size_t e) {
                            RTCIntersectContext context;
                            rtcInitIntersectContext(&context);
                            context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
                            size_t hits = 0;
                            alignas(64) int valid[16];
                            for (size_t i = b; i < e; i += 16) {
                              const int n = static_cast<int>(std::min<size_t>(16, e - i));
                              if (shadow) {
                                alignas(64) RTCRay16 packet;
                                fillPacket(packet, valid, &rays[i], n);
                                rtcOccluded16(valid, es, &context, &packet);
                                for (int k = 0; k < n; ++k) hits += valid[k] && packet.tfar[k] < 0;
                              } else {
                                alignas(64) RTCRayHit16 packet;
                                fillPacket(packet, valid, &rays[i], n);
                                rtcIntersect16(valid, es, &context, &packet);
                                for (int k = 0; k < n; ++k) {
                                  hits +=
                                      valid[k] && packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
                                }
                              }
                            }
                            return hits;
                          },
                          {},
                          {}});

    size_t liveRays = 0;
    for (const Ray& r : set.rays) liveRays += r.tMax >= r.tMin;
    for (int threads : options.threads) {
      for (Contender& c : contenders) {
        c.mraysPerCpuSecond.clear();
        c.mraysPerWallSecond.clear();
      }
      std::vector<size_t> firstHits(contenders.size(), 0);
      for (int round = 0; round < options.runs; ++round) {
        for (size_t k = 0; k < contenders.size(); ++k) {
          Contender& c = contenders[(k + round) % contenders.size()];
          size_t hits = 0;
          const auto [cpu, wall] = runOnce(c.trace, set.rays, threads, hits);
          c.mraysPerCpuSecond.push_back(liveRays / cpu / 1e6);
          c.mraysPerWallSecond.push_back(liveRays / wall / 1e6);
          firstHits[(k + round) % contenders.size()] = hits;
        }
      }
      const double embreeSingle = median(contenders[contenders.size() - 2].mraysPerCpuSecond);
      const double embreePacket = median(contenders.back().mraysPerCpuSecond);
      std::printf(
          "\n| %s, %d thread%s | Mrays per CPU-s per core (median, min..max) | wall "
          "Mrays/s | vs Embree single | vs Embree packet16 | hits |\n|---|---|---:|---:|"
          "---:|---:|\n",
          set.kind.c_str(), threads, threads > 1 ? "s" : "");
      for (size_t k = 0; k < contenders.size(); ++k) {
        const Contender& c = contenders[k];
        const double m = median(c.mraysPerCpuSecond);
        std::printf("| %s | %.2f (%.2f..%.2f) | %.2f | %.2f | %.2f | %zu |\n", c.name.c_str(), m,
                    *std::min_element(c.mraysPerCpuSecond.begin(), c.mraysPerCpuSecond.end()),
                    *std::max_element(c.mraysPerCpuSecond.begin(), c.mraysPerCpuSecond.end()),
                    median(c.mraysPerWallSecond), m / embreeSingle, m / embreePacket, firstHits[k]);
      }
      std::fflush(stdout);
    }
  }
}

std::vector<std::string> commaList(const std::string& list) {
  std::vector<std::string> items;
  for (size_t at = 0; at <= list.size();) {
    const size_t comma = std::min(list.find(',', at), list.size());
    items.push_back(list.substr(at, comma - at));
    at = comma + 1;
  }
  return items;
}

int run(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      options.runs = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--quick") {
      options.quick = true;
    } else if (arg == "--build-only") {
      options.buildOnly = true;
    } else if (arg == "--embree-config" && i + 1 < argc) {
      options.embreeConfig = argv[++i];
    } else if (arg == "--no-variants") {
      options.withVariants = false;
    } else if (arg == "--threads" && i + 1 < argc) {
      options.threads.clear();
      for (const std::string& n : commaList(argv[++i])) {
        options.threads.push_back(std::max(1, std::atoi(n.c_str())));
      }
    } else if (arg == "--kinds" && i + 1 < argc) {
      options.kinds = commaList(argv[++i]);
      for (const std::string& kind : options.kinds) {
        if (kind != "primary" && kind != "incoherent" && kind != "shadow") {
          std::fprintf(stderr, "%s: unknown ray kind '%s' (primary, incoherent, shadow)\n", argv[0],
                       kind.c_str());
          return 2;
        }
      }
    } else if (arg == "--no-generated") {
      options.generatedMeshes = false;
    } else if (arg == "--help" || arg == "-h") {
      std::printf(
          "usage: %s [--runs N] [--quick] [--no-variants] [--threads 1,2] [--build-only] "
          "[--kinds primary,incoherent,shadow] [--no-generated] [--embree-config CFG, e.g. "
          "isa=sse2] [mesh.obj ...]\n"
          "  --kinds         time only these ray sets (all three by default)\n"
          "  --no-generated  leave out the generated sphere and grid: only the OBJ files named\n",
          argv[0]);
      return 0;
    } else {
      options.objs.push_back(arg);
    }
  }
  std::printf(
      "# Prism (%s kernels, the best this CPU runs; x86-64 beside them) against Embree %d.%d.%d "
      "(device config \"%s\"); %d rounds, medians\n",
      instructionSetName(bestInstructionSet(runnableInstructionSets())), RTC_VERSION_MAJOR,
      RTC_VERSION_MINOR, RTC_VERSION_PATCH, options.embreeConfig.c_str(), options.runs);
  std::vector<MeshDesc> meshes;
  if (options.generatedMeshes) {
    meshes.push_back(subdividedSphere(options.quick ? 5 : 7));
    meshes.push_back(displacedGrid(options.quick ? 100 : 708));
  }
  for (const std::string& path : options.objs) {
    for (MeshDesc& mesh : loadObjModel(path, FileLoc{}).meshes) meshes.push_back(std::move(mesh));
  }
  for (const MeshDesc& mesh : meshes) benchmarkMesh(mesh, options);
  return 0;
}

}  // namespace
}  // namespace prism

int main(int argc, char** argv) {
  try {
    return prism::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prism_embree_compare: %s\n", e.what());
    return 1;
  }
}

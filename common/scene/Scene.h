// The render-ready scene a rank builds from a SceneDescription: the world (camera, lights,
// materials, environment, caustic casters) and its geometry (accel/SceneGeometry.h: the
// primitives, BVH and the walks that find hits). Immutable once built and shared by all threads.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "accel/SceneGeometry.h"
#include "accel/Traversal.h"
#include "scene/Camera.h"
#include "scene/CubeMap.h"
#include "scene/SceneDescription.h"
#include "scene/Texture.h"

namespace prism {

// A caustic caster as the photon emitter sees it: a bounding sphere, or an infinite plane.
struct CasterBounds {
  bool plane = false;
  Vec3 center{0.0f};  // sphere
  float radius = 0.0f;
  Vec3 normal{0.0f};  // plane: dot(normal, x) == offset
  float offset = 0.0f;
};

// The caustic bits (kCastsCaustics | kReceivesCaustics) of an object: what its role asks for,
// limited by what its material can do only under Auto (a forced role is taken at its word).
uint8_t causticFlags(CausticRole role, const MaterialDesc& material);

class Scene {
 public:
  explicit Scene(const SceneDescription& description, Traversal traversal = Traversal::WideSimd);
  // The same, with the environment given apart, so a caller that no longer needs the cube-map
  // faces moves them in instead of copying them: for a scene like default.yaml's (six 320x320
  // faces, 7 MiB as floats) the copy and its page faults were a quarter of a small render.
  //   Scene scene(description, std::exchange(description.environment, std::nullopt));
  Scene(const SceneDescription& description, std::optional<CubeMapDesc> environment,
        Traversal traversal = Traversal::WideSimd);
  // The same with the geometry built elsewhere from this description (rank 0 broadcasts it:
  // wire/GeometryCodec.h), which is bit for bit what this rank would build; its kernels are
  // set to the description's instruction set.
  Scene(const SceneDescription& description, std::optional<CubeMapDesc> environment,
        SceneGeometry built);

  // Closest hit in (ray.tMin, ray.tMax); the ray direction must be unit length.
  bool intersect(const Ray& ray, HitRecord& hit) const { return geometry_.intersect(ray, hit); }
  // Whether anything lies on the ray within (ray.tMin, ray.tMax): for shadow rays.
  bool occluded(const Ray& ray) const { return geometry_.occluded(ray); }
  // Up to eight rays at once, for coherent rays (a pixel tile's primary rays or their shadow
  // rays): the same answers as intersect() and occluded() ray by ray. A ray with tMax < tMin is
  // skipped (found/blocked false).
  static constexpr int kPacketSize = SceneGeometry::kPacketSize;
  void intersect8(const Ray* rays, int count, HitRecord* hits, bool* found) const {
    geometry_.intersect8(rays, count, hits, found);
  }
  void occluded8(const Ray* rays, int count, bool* blocked) const {
    geometry_.occluded8(rays, count, blocked);
  }
  // Whether the rays in `live` (bit i: rays[i]) pass the packet walk's direction test (one
  // sign per axis, a spread of at most RayPacket8::kMaxDirectionSpread): a cheap check before
  // building a packet. intersect8/occluded8 check again (finite origins and reciprocals too)
  // and send packets that fail down the single-ray walk one by one.
  static bool coherentDirections(const Ray* rays, uint32_t live) {
    return SceneGeometry::coherentDirections(rays, live);
  }
  // The kernels' instruction set (the settings' choice, Auto resolved to the best this process
  // runs) and how many rays their packet tests take at once: 8 with AVX2, else 4. Tests and
  // benchmarks switch sets to compare them (std::invalid_argument for one this process cannot
  // run).
  InstructionSet instructionSet() const { return geometry_.instructionSet(); }
  int packetLanes() const { return geometry_.packetLanes(); }
  void useInstructionSet(InstructionSet isa) { geometry_.useInstructionSet(isa); }
  // Position, oriented normals and material of a hit found by intersect().
  SurfaceHit surface(const Ray& ray, const HitRecord& hit) const {
    SurfaceHit s;
    geometry_.surface(ray, hit, s);
    return s;
  }
  // The same written into s, for callers that keep it inside a larger record: a returned
  // SurfaceHit copied there would be read back before its stores retire.
  void surface(const Ray& ray, const HitRecord& hit, SurfaceHit& s) const {
    geometry_.surface(ray, hit, s);
  }

  // Radiance of a ray that hits nothing: the environment's finest level seen along direction,
  // or the background colour.
  Color escapedRadiance(const Vec3& direction) const {
    return environment_ ? environment_->lookup(direction) : background_;
  }
  // The same averaged over the footprint of a ray of unit direction whose direction changes by
  // dDdx, dDdy per pixel (CubeMap's mip levels).
  Color escapedRadiance(const Vec3& direction, const Vec3& dDdx, const Vec3& dDdy) const {
    return environment_ ? environment_->lookup(direction, dDdx, dDdy) : background_;
  }
  // The same averaged over a cone of directions `spread` radians wide (a ray cone's spread,
  // math/RayCone.h).
  Color escapedRadiance(const Vec3& direction, float spread) const {
    return environment_ ? environment_->lookup(direction, spread) : background_;
  }
  // Whether escapedRadiance depends on the footprint: a cube map, not a plain background.
  bool escapedRadianceFiltered() const { return environment_.has_value(); }

  const Camera& camera() const { return camera_; }
  const RenderSettings& settings() const { return settings_; }
  const CausticSettings& causticSettings() const { return caustics_; }
  const std::vector<MaterialDesc>& materials() const { return materials_; }
  // What the materials' texture maps index (TextureMap::texture).
  const std::vector<Texture>& textures() const { return textures_; }
  // Indexed by a PrimitiveRef of kind Sphere.
  const std::vector<Sphere>& spheres() const { return geometry_.spheres(); }
  const std::vector<PointLightDesc>& lights() const { return lights_; }
  const Color& ambientLight() const { return ambientLight_; }
  const SceneBuildStats& buildStats() const { return geometry_.stats(); }
  Traversal traversal() const { return geometry_.traversal(); }
  // The face index within its mesh of a triangle hit (for comparing hits with other tracers).
  uint32_t meshFace(const HitRecord& hit) const { return geometry_.meshFace(hit); }
  // Objects whose caustic role includes casting, and whose material can send photons on.
  const std::vector<CasterBounds>& causticCasters() const { return casters_; }
  // Bounds of every bounded primitive (planes excluded).
  const Aabb& bounds() const { return geometry_.bounds(); }
  // The built geometry itself, for sending to other ranks.
  const SceneGeometry& geometry() const { return geometry_; }

 private:
  // The geometry's input: the description's primitives with their caustic bits (meshes as views
  // into the description); the casters are noted on the way.
  GeometryInput geometryInput(const SceneDescription& description, Traversal traversal);

  RenderSettings settings_;
  CausticSettings caustics_;
  Camera camera_;
  Color background_;
  Color ambientLight_;
  std::optional<CubeMap> environment_;
  std::vector<MaterialDesc> materials_;
  std::vector<Texture> textures_;
  std::vector<PointLightDesc> lights_;
  std::vector<CasterBounds> casters_;
  SceneGeometry geometry_;
};

}  // namespace prism

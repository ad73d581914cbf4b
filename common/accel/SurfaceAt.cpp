// A hit's surface: the point put back on its primitive with a bound on its rounding, the
// oriented geometric and shading normals, the material (compiled once per instruction set;
// accel/IsaVariant.h).
#include <cmath>

#include "accel/PrimitiveRef.h"
#include "accel/SceneGeometry.h"
#include "math/RayOffset.h"

namespace prism {

Triangle SceneGeometry::triangle(uint32_t index) const {
  if (!packed_) return triangles_[index];
  const TrianglePack4& pack = packs_[index / TrianglePack4::kWidth].triangles;
  const int lane = static_cast<int>(index % TrianglePack4::kWidth);
  Triangle tri;
  for (int a = 0; a < 3; ++a) {
    tri.v0[a] = pack.v0[a][lane];
    tri.v1[a] = pack.v1[a][lane];
    tri.v2[a] = pack.v2[a][lane];
  }
  // The lane keeps the triangle's number over all meshes; the meshes' first numbers ascend.
  const uint32_t number = pack.triangle[lane];
  tri.mesh = meshOfTriangle(number);
  tri.face = number - meshes_[tri.mesh].firstTriangle;
  return tri;
}

uint32_t SceneGeometry::meshFace(const HitRecord& hit) const {
  return triangle(PrimitiveRef::index(hit.primitive)).face;
}

namespace {

// What SceneGeometry::surface does for every kind once the kind has found the point, its rounding
// bound and its normals. Inlined into each kind's branch: with one tail after the switch, GCC kept
// the branches' results in a shared stack slot and copied them on in eight-byte loads from
// four-byte stores (a store-forwarding stall, a third of what a plane's or a sphere's surface
// cost).
[[gnu::always_inline]] inline void finishSurface(const Ray& ray, float t, const Vec3& position,
                                                 Vec3 positionError, Vec3 geometric, Vec3 shading,
                                                 SurfaceHit& s) {
  // Coordinate by coordinate: copied whole, the point went through the stack the same way.
  s.position.x = position.x;
  s.position.y = position.y;
  s.position.z = position.z;
  // Orient both normals towards the incoming ray; remember which side was hit for refraction.
  s.frontFace = glm::dot(ray.direction, geometric) < 0.0f;
  if (!s.frontFace) {
    geometric = -geometric;
    shading = -shading;
  }
  // Interpolated normals can lean past the geometric horizon at silhouettes; keep them on the
  // ray's side so shading and secondary rays stay consistent.
  if (glm::dot(shading, geometric) < 0.0f) shading = geometric;
  s.geometricNormal = geometric;
  s.shadingNormal = shading;
  s.uvPerWorld = -1.0f;
  s.vertexColor = Color(1.0f);
  positionError += hitDistanceError(t, ray.direction);
  s.leavingDistance = leavingDistance(position, positionError, geometric);
}

// A textured or coloured mesh's texture coordinates and vertex colour at the hit, interpolated
// barycentrically. Apart from finishSurface: plain meshes do not pay for it.
[[gnu::noinline]] void vertexAttributes(const SceneGeometry::MeshShading& mesh, const Triangle& tri,
                                        const HitRecord& hit, SurfaceHit& s) {
  const uint32_t* corner = &mesh.indices[3 * size_t{tri.face}];
  const float w = 1.0f - hit.u - hit.v;
  if (!mesh.uvs.empty()) {
    const Vec2 a = mesh.uvs[corner[0]], b = mesh.uvs[corner[1]], c = mesh.uvs[corner[2]];
    s.uv = w * a + hit.u * b + hit.v * c;
    const Vec2 du = b - a, dv = c - a;
    const float uvArea = std::fabs(du.x * dv.y - du.y * dv.x);
    const float worldArea = glm::length(glm::cross(tri.edge1(), tri.edge2()));
    s.uvPerWorld = worldArea > 0.0f ? std::sqrt(uvArea / worldArea) : 0.0f;
  }
  if (!mesh.colors.empty()) {
    s.vertexColor = w * mesh.colors[corner[0]] + hit.u * mesh.colors[corner[1]] +
                    hit.v * mesh.colors[corner[2]];
  }
}

}  // namespace

void SceneGeometry::Kernels::surface(const SceneGeometry& g, const Ray& ray, const HitRecord& hit,
                                     SurfaceHit& s) {
  // Each kind puts the point back on its surface with a bound on the rounding per axis
  // (math/RayOffset.h): rays leaving it start just outside that bound, widened by the rounding of
  // the incoming ray's distance (surfaces nearer each other than that cannot be ordered).
  const uint32_t index = PrimitiveRef::index(hit.primitive);
  switch (PrimitiveRef::kind(hit.primitive)) {
    case PrimitiveKind::Triangle: {
      const Triangle tri = g.triangle(index);
      const MeshShading& mesh = g.meshes_[tri.mesh];
      Vec3 positionError;
      const Vec3 position = tri.pointAt(hit.u, hit.v, positionError);
      Vec3 geometric = glm::normalize(glm::cross(tri.edge1(), tri.edge2()));
      Vec3 shading = geometric;
      if (!mesh.normals.empty()) {
        const uint32_t* corner = &mesh.indices[3 * tri.face];
        const Vec3 interpolated = (1.0f - hit.u - hit.v) * mesh.normals[corner[0]] +
                                  hit.u * mesh.normals[corner[1]] + hit.v * mesh.normals[corner[2]];
        const float length = glm::length(interpolated);
        if (length > 0.0f) shading = interpolated / length;
        // Authored normals define outside; the winding order may disagree with them.
        if (glm::dot(geometric, shading) < 0.0f) geometric = -geometric;
      }
      s.material = mesh.faceMaterials.empty() ? mesh.material : mesh.faceMaterials[tri.face];
      s.caustic = mesh.caustic;
      finishSurface(ray, hit.t, position, positionError, geometric, shading, s);
      if (!mesh.uvs.empty() || !mesh.colors.empty()) vertexAttributes(mesh, tri, hit, s);
      return;
    }
#define PRISM_SHAPE_SURFACE(Shape, plural)                                          \
  case PrimitiveKind::Shape: {                                                      \
    const Shape& shape = g.plural##_[index];                                        \
    Vec3 positionError, normal;                                                     \
    const Vec3 position = shape.surfacePoint(ray.at(hit.t), positionError, normal); \
    s.material = shape.materialId();                                                \
    s.caustic = g.plural##Caustic_[index];                                          \
    finishSurface(ray, hit.t, position, positionError, normal, normal, s);          \
    return;                                                                         \
  }
      PRISM_SHAPE_KINDS(PRISM_SHAPE_SURFACE)
#undef PRISM_SHAPE_SURFACE
    case PrimitiveKind::Plane: {
      Vec3 positionError;
      const Vec3 position = g.planes_[index].surfacePoint(ray.at(hit.t), positionError);
      s.material = g.planes_[index].material;
      s.caustic = g.planeCaustic_[index];
      finishSurface(ray, hit.t, position, positionError, g.planes_[index].normal,
                    g.planes_[index].normal, s);
      return;
    }
  }
}

}  // namespace prism

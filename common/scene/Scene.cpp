#include "scene/Scene.h"

#include <utility>

namespace prism {
namespace {

bool anyPositive(const Color& c) {
  return c.x > 0.0f || c.y > 0.0f || c.z > 0.0f;
}

CasterBounds boundingSphere(const Aabb& b) {
  const Ball ball = ballAround(b);
  CasterBounds c;
  c.center = ball.center;
  c.radius = ball.radius;
  return c;
}

std::vector<Texture> texturesOf(const std::vector<TextureDesc>& descs) {
  std::vector<Texture> textures;
  textures.reserve(descs.size());
  for (const TextureDesc& desc : descs) textures.emplace_back(desc);
  return textures;
}

std::vector<MaterialDesc> withDefaultMaterial(std::vector<MaterialDesc> materials) {
  if (materials.empty()) materials.emplace_back();  // primitives default to material 0
  return materials;
}

}  // namespace

uint8_t causticFlags(CausticRole role, const MaterialDesc& m) {
  const bool specular = anyPositive(m.reflectance) || anyPositive(m.transmittance);
  const bool diffuse = m.checker.has_value() || anyPositive(m.diffuse);  // a texture multiplies it
  switch (role) {
    case CausticRole::Auto:
      return static_cast<uint8_t>((specular ? kCastsCaustics : 0) |
                                  (diffuse ? kReceivesCaustics : 0));
    case CausticRole::Cast:
      return kCastsCaustics;
    case CausticRole::Receive:
      return kReceivesCaustics;
    case CausticRole::Both:
      return kCastsCaustics | kReceivesCaustics;
    case CausticRole::Off:
      return 0;
  }
  return 0;
}

Scene::Scene(const SceneDescription& d, Traversal traversal) : Scene(d, d.environment, traversal) {}

Scene::Scene(const SceneDescription& d, std::optional<CubeMapDesc> environment, Traversal traversal)
    : settings_(d.render),
      caustics_(d.caustics),
      camera_(d.camera, d.render.width, d.render.height),
      background_(d.background),
      ambientLight_(d.ambientLight),
      materials_(withDefaultMaterial(d.materials)),
      textures_(texturesOf(d.textures)),
      lights_(d.lights),
      geometry_(geometryInput(d, traversal)) {
  if (environment) environment_.emplace(std::move(*environment));
  settings_.instructionSet = geometry_.instructionSet();  // Auto resolved
}

Scene::Scene(const SceneDescription& d, std::optional<CubeMapDesc> environment, SceneGeometry built)
    : settings_(d.render),
      caustics_(d.caustics),
      camera_(d.camera, d.render.width, d.render.height),
      background_(d.background),
      ambientLight_(d.ambientLight),
      materials_(withDefaultMaterial(d.materials)),
      textures_(texturesOf(d.textures)),
      lights_(d.lights),
      geometry_(std::move(built)) {
  geometryInput(d, geometry_.traversal());  // for the casters: the build itself is done
  if (environment) environment_.emplace(std::move(*environment));
  geometry_.useInstructionSet(d.render.instructionSet);
  settings_.instructionSet = geometry_.instructionSet();  // Auto resolved
}

GeometryInput Scene::geometryInput(const SceneDescription& d, Traversal traversal) {
  GeometryInput in;
  in.triangleTest = d.render.triangleTest;
  in.traversal = traversal;
  in.instructionSet = d.render.instructionSet;
  const auto materialOf = [&](MaterialId id) -> const MaterialDesc& {
    return materials_[id < materials_.size() ? id : 0];
  };
  const auto addShapes = [&](const auto& descs, auto& shapes, std::vector<uint8_t>& caustic) {
    for (const auto& desc : descs) {
      shapes.push_back(desc.shape());
      caustic.push_back(causticFlags(desc.caustic, materialOf(desc.material)));
      if (caustic.back() & kCastsCaustics) {
        const Ball ball = shapes.back().boundingBall();
        CasterBounds c;
        c.center = ball.center;
        c.radius = ball.radius;
        casters_.push_back(c);
      }
    }
  };
#define PRISM_ADD_SHAPES(Shape, plural) addShapes(d.plural, in.plural, in.plural##Caustic);
  PRISM_SHAPE_KINDS(PRISM_ADD_SHAPES)
#undef PRISM_ADD_SHAPES
  std::vector<uint8_t> used;  // by the faces of one mesh
  for (const MeshDesc& mesh : d.meshes) {
    // A mesh of several materials has the caustic bits of all of them.
    uint8_t caustic = causticFlags(mesh.caustic, materialOf(mesh.material));
    if (!mesh.faceMaterials.empty()) {
      used.assign(materials_.size(), 0);
      caustic = 0;
      for (const MaterialId id : mesh.faceMaterials) {
        uint8_t& seen = used[id < materials_.size() ? id : 0];
        if (seen) continue;
        seen = 1;
        caustic |= causticFlags(mesh.caustic, materialOf(id));
      }
    }
    in.meshes.push_back({mesh.positions, mesh.indices, mesh.normals, mesh.uvs, mesh.colors,
                         mesh.faceMaterials, mesh.material, caustic});
    if (caustic & kCastsCaustics) {
      Aabb meshBounds;
      for (const Vec3& p : mesh.positions) meshBounds.extend(p);
      if (!meshBounds.empty()) casters_.push_back(boundingSphere(meshBounds));
    }
  }
  for (const PlaneDesc& p : d.planes) {
    const Vec3 n = glm::normalize(p.normal);
    in.planes.push_back({n, glm::dot(n, p.point), p.material});
    in.planeCaustic.push_back(causticFlags(p.caustic, materialOf(p.material)));
    if (in.planeCaustic.back() & kCastsCaustics) {
      CasterBounds c;
      c.plane = true;
      c.normal = in.planes.back().normal;
      c.offset = in.planes.back().offset;
      casters_.push_back(c);
    }
  }
  return in;
}

}  // namespace prism

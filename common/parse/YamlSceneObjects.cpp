// The objects section of Prism's YAML scenes (docs/scene-format.md, "objects"): each kind of
// geometry/ShapeKinds.h by the keys it declares, planes, cylinders, single triangles and meshes
// from files with their transforms, and the materials objects name. The key tables below are
// exactly what the parser accepts for them.
#include <array>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>
#include <string_view>
#include <utility>

#include "parse/ModelFile.h"
#include "parse/YamlSceneReader.h"
#include "scene/GeometryMemory.h"
#include "scene/MeshBudget.h"

namespace prism {
namespace {

using yaml::describe;
using yaml::Entry;
using yaml::joined;
using yaml::KeyTable;
using yaml::Mapping;
using yaml::shown;

// The shapes of geometry/ShapeKinds.h by their own names, then the other objects.
#define PRISM_SHAPE_NAME(Shape, plural) Shape##Desc::kName,
constexpr std::string_view kObjectKinds[] = {PRISM_SHAPE_KINDS(PRISM_SHAPE_NAME) "plane",
                                             "cylinder", "triangle", "mesh"};
#undef PRISM_SHAPE_NAME
// A shape's keys: its own (geometry/ShapeKeys.h), then the two every object takes.
template <class Desc>
constexpr auto shapeKeyNames() {
  constexpr auto keys = Desc::keys();
  std::array<std::string_view, keys.size() + 2> names{};
  for (size_t i = 0; i < keys.size(); ++i) names[i] = keys[i].name;
  names[keys.size()] = "material";
  names[keys.size() + 1] = "caustic";
  return names;
}
template <class Desc>
constexpr auto kShapeKeys = shapeKeyNames<Desc>();
constexpr std::string_view kPlaneKeys[] = {"point", "normal", "material", "caustic"};
constexpr std::string_view kCylinderKeys[] = {"base", "apex", "radius", "material", "caustic"};
constexpr std::string_view kTriangleKeys[] = {"vertices", "normals", "material", "caustic"};
constexpr std::string_view kMeshKeys[] = {"file",    "material", "transform",
                                          "caustic", "camera",   "lights"};
constexpr std::string_view kTransformKeys[] = {"scale", "rotate", "translate"};

constexpr std::string_view kDefaultMaterialName = "default";

std::vector<std::string> toStrings(KeyTable keys) {
  return {keys.begin(), keys.end()};
}

}  // namespace

void addObjectKeys(std::map<std::string, std::vector<std::string>>& keys) {
  keys.emplace("objects", toStrings(kObjectKinds));
#define PRISM_SHAPE_KEYS(Shape, plural) \
  keys.emplace(std::string(Shape##Desc::kName), toStrings(kShapeKeys<Shape##Desc>));
  PRISM_SHAPE_KINDS(PRISM_SHAPE_KEYS)
#undef PRISM_SHAPE_KEYS
  keys.emplace("plane", toStrings(kPlaneKeys));
  keys.emplace("cylinder", toStrings(kCylinderKeys));
  keys.emplace("triangle", toStrings(kTriangleKeys));
  keys.emplace("mesh", toStrings(kMeshKeys));
  keys.emplace("transform", toStrings(kTransformKeys));
}

void YamlSceneReader::readObjects(const Entry& section) {
  for (const YAML::Node& item : list(section, "objects")) {
    const FileLoc at = itemLoc(item, loc(section));
    if (!item.IsMap()) {
      fail(at, "expected an object such as 'sphere: {...}' (one of: " + joined(kObjectKinds) +
                   "), found " + describe(item));
    }
    const Mapping kinds = mapping(item, at, "object", kObjectKinds, "kind");
    if (kinds.entries.empty()) {
      fail(at, "empty object entry (expected one of: " + joined(kObjectKinds) + ")");
    }
    if (kinds.entries.size() > 1) {
      fail(loc(kinds.entries[1].keyNode),
           "an object entry holds exactly one object, found '" + kinds.entries[0].key + "' and '" +
               kinds.entries[1].key + "'; start each object with its own '-'");
    }
    const Entry& object = kinds.entries.front();
#define PRISM_READ_SHAPE(Shape, plural) \
  if (object.key == Shape##Desc::kName) readShape(object, scene_.plural);
    PRISM_SHAPE_KINDS(PRISM_READ_SHAPE)
#undef PRISM_READ_SHAPE
    if (object.key == "plane") readPlane(object);
    if (object.key == "cylinder") readCylinder(object);
    if (object.key == "triangle") readTriangle(object);
    if (object.key == "mesh") readMesh(object);
  }
}

CausticRole YamlSceneReader::causticRole(const Mapping& m) const {
  const Entry* e = m.find("caustic");
  return e ? choice(*e, kCausticRoleNames) : CausticRole::Auto;
}

MaterialId YamlSceneReader::material(const Mapping& m) {
  const Entry* e = m.find("material");
  const std::string name = e ? string(*e) : std::string(kDefaultMaterialName);
  if (auto it = materialIds_.find(name); it != materialIds_.end()) return it->second;
  if (name == kDefaultMaterialName) return defaultMaterial();
  std::string defined;
  for (const MaterialDesc& mat : scene_.materials) {
    if (mat.name == kDefaultMaterialName && defaultMaterial_) continue;
    defined += (defined.empty() ? "" : ", ") + mat.name;
  }
  fail(loc(*e),
       "unknown material " + shown(name) +
           (defined.empty() ? " (no materials are defined)" : " (defined: " + defined + ")"));
}

MaterialId YamlSceneReader::defaultMaterial() {
  if (!defaultMaterial_) {
    MaterialDesc mat;
    mat.name = std::string(kDefaultMaterialName);
    mat.loc = FileLoc{path_};
    defaultMaterial_ = static_cast<MaterialId>(scene_.materials.size());
    scene_.materials.push_back(std::move(mat));
  }
  return *defaultMaterial_;
}

template <class Desc>
void YamlSceneReader::readShape(const Entry& object, std::vector<Desc>& shapes) {
  const Mapping m = mapping(object, Desc::kName, kShapeKeys<Desc>);
  Desc d;
  d.loc = m.loc;
  for (const ShapeKey<Desc>& key : Desc::keys()) {
    const Entry* e = key.required ? &m.require(key.name) : m.find(key.name);
    if (!e) continue;
    switch (key.value) {
      case KeyValue::Point:
        d.*key.vector = vec3(*e);
        break;
      case KeyValue::Direction:
        d.*key.vector = direction(*e);
        break;
      case KeyValue::Positive:
        d.*key.number = positive(*e);
        break;
      case KeyValue::NonNegative:
        d.*key.number = nonNegative(*e);
        break;
    }
  }
  if (const std::optional<ShapeProblem> problem = d.problem()) {
    fail(loc(m.require(problem->key)), problem->message);
  }
  d.material = material(m);
  d.caustic = causticRole(m);
  shapes.push_back(d);
}

void YamlSceneReader::readPlane(const Entry& object) {
  const Mapping m = mapping(object, "plane", kPlaneKeys);
  PlaneDesc p;
  p.loc = m.loc;
  p.point = vec3(m.require("point"));
  p.normal = direction(m.require("normal"));
  p.material = material(m);
  p.caustic = causticRole(m);
  scene_.planes.push_back(p);
}

void YamlSceneReader::readCylinder(const Entry& object) {
  const Mapping m = mapping(object, "cylinder", kCylinderKeys);
  ConeDesc c;
  c.loc = m.loc;
  c.base = vec3(m.require("base"));
  c.apex = vec3(m.require("apex"));
  if (c.base == c.apex) fail(loc(m.require("apex")), "'apex' must differ from 'base'");
  c.baseRadius = c.apexRadius = positive(m.require("radius"));
  c.material = material(m);
  c.caustic = causticRole(m);
  scene_.cones.push_back(c);
}

std::array<Vec3, 3> YamlSceneReader::threeVectors(const Entry& e, std::string_view what) const {
  if (!e.value.IsSequence() || e.value.size() != 3) {
    fail(loc(e), "expected a list of 3 " + std::string(what) + " for '" + e.key + "', found " +
                     describe(e.value));
  }
  std::array<Vec3, 3> out;
  for (int i = 0; i < 3; ++i) {
    const YAML::Node item = e.value[i];
    out[i] = vec3(item, itemLoc(item, loc(e)), e.key);
  }
  return out;
}

void YamlSceneReader::readTriangle(const Entry& object) {
  const Mapping m = mapping(object, "triangle", kTriangleKeys);
  MeshDesc mesh;
  mesh.source = "triangle";
  mesh.loc = m.loc;
  const auto vertices = threeVectors(m.require("vertices"), "points");
  mesh.positions.assign(vertices.begin(), vertices.end());
  if (const Entry* e = m.find("normals")) {
    for (const Vec3& n : threeVectors(*e, "normals")) {
      if (n == Vec3(0.0f)) fail(loc(*e), "'normals' must not contain the zero vector");
      mesh.normals.push_back(glm::normalize(n));
    }
  }
  mesh.indices = {0, 1, 2};
  mesh.material = material(m);
  mesh.caustic = causticRole(m);
  scene_.meshes.push_back(std::move(mesh));
}

void YamlSceneReader::readMesh(const Entry& object) {
  const Mapping m = mapping(object, "mesh", kMeshKeys);
  const Entry& fileEntry = m.require("file");
  const std::string file = string(fileEntry);
  const std::filesystem::path resolved = resolve(file);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(resolved, ec)) {
    const bool exists = std::filesystem::exists(resolved, ec);
    fail(loc(fileEntry), "mesh file " + shown(file) +
                             (exists ? " is not a regular file" : " not found") + " (looked for '" +
                             resolved.string() + "')");
  }
  ModelDesc model = loadModelFile(resolved.string(), loc(fileEntry), meshBudget_.remaining());
  size_t positions = 0;
  for (const MeshDesc& mesh : model.meshes) positions += mesh.positions.size();
  meshBudget_.spend(meshBuildBytes(model.triangleCount(), positions));
  // Its textures too: the next model is read against what is left.
  for (const TextureDesc& t : model.textures) meshBudget_.spend(textureMemoryBytes(t));
  if (model.triangleCount() == 0)
    fail(loc(fileEntry), "mesh file " + shown(file) + " has no triangles");
  for (MeshDesc& mesh : model.meshes) {
    if (mesh.source.empty()) mesh.source = resolved.string();
  }
  if (const Entry* e = m.find("transform")) applyTransform(*e, model);
  ModelPlacement placement;
  // The model's own materials unless the scene names one for the whole mesh.
  if (m.find("material") || model.materials.empty()) placement.material = material(m);
  placement.caustic = causticRole(m);
  placement.loc = m.loc;
  if (const Entry* e = m.find("camera")) {
    placement.takeCamera = boolean(*e);
    if (placement.takeCamera && !model.camera) {
      fail(loc(*e), "mesh file " + shown(file) + " has no camera to take");
    }
  }
  if (const Entry* e = m.find("lights")) {
    placement.takeLights = boolean(*e);
    if (placement.takeLights && model.lights.empty()) {
      scene_.warnings.push_back(loc(*e).toString() + ": mesh file " + shown(file) +
                                " has no lights to take");
    }
  }
  placeModel(std::move(model), placement, scene_);
}

void YamlSceneReader::applyTransform(const Entry& section, ModelDesc& model) const {
  const Mapping m = mapping(section, "transform", kTransformKeys);
  Vec3 scale(1.0f), rotate(0.0f), translate(0.0f);
  if (const Entry* e = m.find("scale")) {
    scale = e->value.IsScalar() ? Vec3(number(*e)) : vec3(*e);
    if (scale.x == 0.0f || scale.y == 0.0f || scale.z == 0.0f) {
      fail(loc(*e), "'scale' must not be zero in any axis (the mesh would be flat)");
    }
  }
  if (const Entry* e = m.find("rotate")) rotate = vec3(*e);
  if (const Entry* e = m.find("translate")) translate = vec3(*e);

  glm::mat4 r(1.0f);
  r = glm::rotate(r, glm::radians(rotate.z), Vec3(0, 0, 1));
  r = glm::rotate(r, glm::radians(rotate.y), Vec3(0, 1, 0));
  r = glm::rotate(r, glm::radians(rotate.x), Vec3(1, 0, 0));
  const glm::mat3 rotation(r);
  const glm::mat3 linear = rotation * glm::mat3(glm::scale(glm::mat4(1.0f), scale));
  const glm::mat3 normalMatrix =
      rotation * glm::mat3(glm::scale(glm::mat4(1.0f), Vec3(1.0f) / scale));

  for (MeshDesc& mesh : model.meshes) {
    for (Vec3& p : mesh.positions) p = linear * p + translate;
    for (Vec3& n : mesh.normals) n = glm::normalize(normalMatrix * n);
    // A mirroring scale turns the winding around; swap it back so that the winding still
    // agrees with the vertex normals.
    if (scale.x * scale.y * scale.z < 0.0f) {
      for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
      }
    }
  }
  // The model's camera and lights move with it (a scene takes them on request).
  if (model.camera) {
    model.camera->position = linear * model.camera->position + translate;
    model.camera->lookAt = linear * model.camera->lookAt + translate;
    model.camera->up = glm::normalize(linear * model.camera->up);
  }
  for (PointLightDesc& light : model.lights) light.position = linear * light.position + translate;
}

}  // namespace prism

// Prism's YAML scene format, read with yaml-cpp. docs/scene-format.md is the reference; the key
// tables below are exactly what the parser accepts, and a test checks that each is documented.
//
// This file is the schema: which sections and keys exist, their types, defaults and limits.
// Reading and checking the YAML itself (positions, types, unknown keys) is parse/CheckedYaml.h;
// enumerated values and numeric limits come from scene/SettingNames.h and SettingLimits.h, which
// the command line shares.
#include "parse/YamlSceneParser.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <optional>
#include <string_view>
#include <utility>

#include "image/ImageIo.h"
#include "parse/CheckedYaml.h"
#include "parse/MeshFile.h"
#include "parse/PrintableText.h"
#include "scene/MeshBudget.h"
#include "scene/SceneValidation.h"
#include "util/MemoryBudget.h"
#include "util/Parallel.h"

namespace prism {
namespace {

using yaml::CheckedYaml;
using yaml::describe;
using yaml::Entry;
using yaml::joined;
using yaml::KeyTable;
using yaml::Mapping;
using yaml::shown;

constexpr std::string_view kTopLevelKeys[] = {"camera",  "render",      "background",
                                              "ambient", "environment", "materials",
                                              "lights",  "objects",     "caustics"};
constexpr std::string_view kCameraKeys[] = {"projection", "position", "look_at", "up",
                                            "fov",        "width",    "near"};
constexpr std::string_view kRenderKeys[] = {"width",     "height",           "samples",
                                            "max_depth", "min_contribution", "seed",
                                            "exposure",  "triangle_test"};
constexpr std::string_view kCausticsKeys[] = {
    "method",          "photons",     "gather",         "noise",     "max_radius",
    "filter",          "max_bounces", "progressive",    "passes",    "alpha",
    "radius",          "time_budget", "map_resolution", "map_steps", "map_blur_sigma",
    "map_blur_radius", "map_paths"};
constexpr std::string_view kEnvironmentKeys[] = {"cubemap", "scale"};
// In the OpenGL cube-map order of CubeMapDesc::faces: +X, -X, +Y, -Y, +Z, -Z.
constexpr std::string_view kCubeMapKeys[] = {"px", "nx", "py", "ny", "pz", "nz"};
constexpr std::string_view kMaterialKeys[] = {
    "name",      "ambient",     "diffuse",       "checker", "specular",
    "shininess", "reflectance", "transmittance", "ior",     "fresnel"};
constexpr std::string_view kCheckerKeys[] = {"colors", "scale"};
constexpr std::string_view kLightKeys[] = {"position", "intensity", "attenuation"};
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
constexpr std::string_view kMeshKeys[] = {"file", "material", "transform", "caustic"};
constexpr std::string_view kTransformKeys[] = {"scale", "rotate", "translate"};

constexpr std::string_view kDefaultMaterialName = "default";

// The scene schema, written in the checked reader's vocabulary (number, mapping, choice, ...).
class YamlSceneReader : private CheckedYaml {
 public:
  YamlSceneReader(const std::string& path, const MemoryLimit& limit)
      : CheckedYaml(path),
        path_(path),
        baseDir_(std::filesystem::path(path).parent_path()),
        meshBudget_(limit, "the meshes before this one") {}

  SceneDescription read(const std::string& text) {
    const YAML::Node root = load(text);
    if (root.IsNull()) throw SceneError(FileLoc{path_}, "scene is empty");
    if (!root.IsMap()) {
      throw SceneError(loc(root.Mark()), "expected a mapping of scene sections (" +
                                             joined(kTopLevelKeys) + ") at the top level, found " +
                                             describe(root));
    }
    try {
      return readScene(root);
    } catch (const YAML::Exception& e) {
      // Nothing below should throw these, but none may escape without a position.
      throw SceneError(loc(e.mark), "invalid YAML: " + printableExcerpt(e.msg, 200));
    }
  }

 private:
  std::string path_;
  std::filesystem::path baseDir_;
  MemoryBudget meshBudget_;  // each mesh is read against the limit less the meshes before it
  SceneDescription scene_;
  std::map<std::string, MaterialId, std::less<>> materialIds_;
  std::optional<MaterialId> defaultMaterial_;

  std::filesystem::path resolve(const std::string& file) const {
    const std::filesystem::path p(file);
    return p.is_absolute() ? p : baseDir_ / p;
  }

  // ---- sections ---------------------------------------------------------------------------

  SceneDescription readScene(const YAML::Node& root) {
    scene_.sourcePath = path_;
    scene_.camera.loc = FileLoc{path_};
    const Mapping top = mapping(root, loc(root), "top-level", kTopLevelKeys);
    // Materials come first so objects can refer to them wherever they appear in the file.
    if (const Entry* e = top.find("materials")) readMaterials(*e);
    if (const Entry* e = top.find("camera")) readCamera(*e);
    if (const Entry* e = top.find("render")) readRender(*e);
    if (const Entry* e = top.find("caustics")) readCaustics(*e);
    if (const Entry* e = top.find("background")) scene_.background = color(*e);
    if (const Entry* e = top.find("ambient")) scene_.ambientLight = color(*e);
    if (const Entry* e = top.find("environment")) readEnvironment(*e);
    if (const Entry* e = top.find("lights")) readLights(*e);
    if (const Entry* e = top.find("objects")) readObjects(*e);
    try {
      validate(scene_);  // each key was checked where it was read: this is the backstop
    } catch (const SettingError& e) {
      fail(FileLoc{path_}, e.what());
    }
    return std::move(scene_);
  }

  void readCamera(const Entry& section) {
    const Mapping m = mapping(section, "camera", kCameraKeys);
    CameraDesc& cam = scene_.camera;
    cam.loc = m.loc;
    if (const Entry* e = m.find("projection")) cam.projection = choice(*e, kProjectionNames);
    if (const Entry* e = m.find("position")) cam.position = vec3(*e);
    if (const Entry* e = m.find("look_at")) cam.lookAt = vec3(*e);
    if (const Entry* e = m.find("up")) cam.up = vec3(*e);
    if (const Entry* e = m.find("fov")) {
      cam.fovDegrees = number(*e);
      if (!(cam.fovDegrees > 0.0f && cam.fovDegrees < 180.0f)) {
        fail(loc(*e), "'fov' must be between 0 and 180 degrees (exclusive), found " + text(*e));
      }
    }
    if (const Entry* e = m.find("width")) cam.width = positive(*e);
    if (const Entry* e = m.find("near")) cam.nearClip = nonNegative(*e);

    // Checked in double so that nearly coincident points cannot underflow to a zero vector.
    const glm::dvec3 view = glm::dvec3(cam.lookAt) - glm::dvec3(cam.position);
    if (glm::length(view) == 0.0) {
      const Entry* at = m.find("look_at") ? m.find("look_at") : m.find("position");
      fail(at ? loc(*at) : m.loc,
           "camera 'position' and 'look_at' are the same point, so there is no view direction");
    }
    const Entry* upEntry = m.find("up");
    // Without an 'up' key the default is at fault: point at the camera section.
    const FileLoc upAt = upEntry ? loc(*upEntry) : loc(section.keyNode);
    if (glm::length(glm::dvec3(cam.up)) == 0.0) fail(upAt, "'up' must not be the zero vector");
    const double sine =
        glm::length(glm::cross(glm::normalize(view), glm::normalize(glm::dvec3(cam.up))));
    if (sine < 1e-6) {
      fail(upAt, "camera 'up' is parallel to the view direction (from 'position' to 'look_at')");
    }
  }

  void readRender(const Entry& section) {
    const Mapping m = mapping(section, "render", kRenderKeys);
    RenderSettings& r = scene_.render;
    if (const Entry* e = m.find("width")) r.width = static_cast<int>(integer(*e, limits::kWidth));
    if (const Entry* e = m.find("height")) {
      r.height = static_cast<int>(integer(*e, limits::kHeight));
    }
    if (const Entry* e = m.find("samples")) {
      r.samplesPerPixel = static_cast<int>(integer(*e, limits::kSamples));
    }
    if (const Entry* e = m.find("max_depth")) {
      r.maxDepth = static_cast<int>(integer(*e, limits::kMaxDepth));
    }
    if (const Entry* e = m.find("min_contribution")) r.minContribution = nonNegative(*e);
    if (const Entry* e = m.find("seed")) r.seed = unsignedInteger(*e);
    if (const Entry* e = m.find("exposure")) r.exposure = positive(*e);
    if (const Entry* e = m.find("triangle_test")) r.triangleTest = choice(*e, kTriangleTestNames);
  }

  void readCaustics(const Entry& section) {
    const Mapping m = mapping(section, "caustics", kCausticsKeys);
    CausticSettings& c = scene_.caustics;
    if (const Entry* e = m.find("method")) c.method = choice(*e, kCausticMethodNames);
    if (const Entry* e = m.find("photons")) {
      c.photons = static_cast<uint64_t>(integer(*e, limits::kPhotons));
    }
    if (const Entry* e = m.find("gather")) {
      if (e->value.IsScalar() && e->value.Scalar() == "auto")
        c.automaticGather = true;
      else
        c.gather = static_cast<int>(integer(*e, limits::kGather));
    }
    if (const Entry* e = m.find("noise")) {
      c.gatherNoise = positive(*e);
      if (c.gatherNoise < limits::kSmallestGatherNoise || c.gatherNoise > 1.0f)
        fail(loc(*e), "'noise' must lie between 0.0032 and 1, found " + text(*e));
    }
    if (const Entry* e = m.find("max_radius")) c.maxRadius = nonNegative(*e);
    if (const Entry* e = m.find("filter")) c.filter = choice(*e, kPhotonFilterNames);
    if (const Entry* e = m.find("max_bounces")) {
      c.maxBounces = static_cast<int>(integer(*e, limits::kMaxBounces));
    }
    if (const Entry* e = m.find("progressive")) c.progressive = boolean(*e);
    if (const Entry* e = m.find("passes"))
      c.passes = static_cast<int>(integer(*e, limits::kPasses));
    if (const Entry* e = m.find("alpha")) {
      c.alpha = number(*e);
      if (!(c.alpha > 0.0f && c.alpha < 1.0f)) {
        fail(loc(*e), "'alpha' must lie strictly between 0 and 1, found " + text(*e));
      }
    }
    if (const Entry* e = m.find("radius")) c.radius = nonNegative(*e);
    if (const Entry* e = m.find("time_budget")) {
      c.timeBudgetSeconds = nonNegative(*e);
      // A budget bounds progressive passes, so it asks for them (a classic render is one pass,
      // which the budget could not shorten: it was silently ignored).
      if (c.timeBudgetSeconds > 0.0) {
        if (const Entry* p = m.find("progressive"); p && !c.progressive) {
          fail(loc(*p),
               "'progressive' is false, but 'time_budget' bounds progressive passes: remove "
               "one of them");
        }
        c.progressive = true;
        // A budget that gives no pass count runs passes until it ends.
        if (!m.find("passes")) c.passes = kPassesUntilBudget;
      }
    }
    if (const Entry* e = m.find("map_resolution")) {
      c.mapResolution = static_cast<int>(integer(*e, limits::kMapResolution));
    }
    if (const Entry* e = m.find("map_steps")) {
      c.mapSteps = static_cast<int>(integer(*e, limits::kMapSteps));
    }
    if (const Entry* e = m.find("map_blur_sigma")) c.mapBlurSigma = nonNegative(*e);
    if (const Entry* e = m.find("map_blur_radius")) {
      c.mapBlurRadius = static_cast<int>(integer(*e, limits::kMapBlurRadius));
    }
    if (const Entry* e = m.find("map_paths")) c.mapPaths = choice(*e, kCausticMapPathsNames);
  }

  CausticRole causticRole(const Mapping& m) const {
    const Entry* e = m.find("caustic");
    return e ? choice(*e, kCausticRoleNames) : CausticRole::Auto;
  }

  void readEnvironment(const Entry& section) {
    const Mapping m = mapping(section, "environment", kEnvironmentKeys);
    CubeMapDesc cube;
    if (const Entry* e = m.find("scale")) cube.scale = nonNegative(*e);
    const Mapping faces = mapping(m.require("cubemap"), "cubemap", kCubeMapKeys);
    // Every face must be named before any is read, so a missing key is reported as such.
    for (std::string_view key : kCubeMapKeys) faces.require(key);
    constexpr size_t kFaces = std::size(kCubeMapKeys);
    std::array<std::string, kFaces> files, readErrors;
    for (size_t i = 0; i < kFaces; ++i) {
      cube.paths[i] = string(faces.require(kCubeMapKeys[i]));
      files[i] = resolve(cube.paths[i]).string();
    }
    // The six decodes are independent (default.yaml's 320² PNGs take 4-6 ms each): they run on
    // the cores at once, and a failure is reported below for the first failing face in order.
    // 8-bit faces are kept as their bytes, the others as radiance.
    parallelFor(kFaces, 0, [&](uint64_t i) {
      try {
        if (std::optional<SrgbImage> bytes = readSrgbImage(files[i])) {
          cube.srgbFaces[i] = std::move(*bytes);
        } else {
          cube.faces[i] = readImage(files[i]);
        }
      } catch (const std::exception& error) {
        readErrors[i] = error.what();
        if (readErrors[i].empty()) readErrors[i] = "unreadable";
      }
    });
    for (size_t i = 0; i < kFaces; ++i) {
      const Entry& face = faces.require(kCubeMapKeys[i]);
      if (!readErrors[i].empty())
        fail(loc(face), "cube-map face '" + face.key + "': " + readErrors[i]);
      const int width = cube.srgbFaces[i].width + cube.faces[i].width;  // one of them is 0
      const int height = cube.srgbFaces[i].height + cube.faces[i].height;
      const int firstWidth = cube.srgbFaces[0].width + cube.faces[0].width;
      if (width <= 0 || width != height) {
        fail(loc(face), "cube-map face '" + face.key + "' is " + std::to_string(width) + "x" +
                            std::to_string(height) + "; faces must be square");
      }
      if (i > 0 && width != firstWidth) {
        fail(loc(face), "cube-map face '" + face.key + "' is " + std::to_string(width) +
                            " pixels wide but 'px' is " + std::to_string(firstWidth) +
                            "; all faces must be the same size");
      }
    }
    // All six as bytes, or all as radiance (a face of another kind among 8-bit ones).
    const auto isBytes = [](const SrgbImage& face) { return !face.empty(); };
    if (!std::all_of(cube.srgbFaces.begin(), cube.srgbFaces.end(), isBytes)) {
      for (size_t i = 0; i < kFaces; ++i) {
        if (isBytes(cube.srgbFaces[i])) cube.faces[i] = linearFromSrgb(cube.srgbFaces[i]);
        cube.srgbFaces[i] = SrgbImage();
      }
    }
    scene_.environment = std::move(cube);
  }

  void readMaterials(const Entry& section) {
    for (const YAML::Node& item : list(section, "materials")) {
      const Mapping m = mapping(item, itemLoc(item, loc(section)), "material", kMaterialKeys);
      MaterialDesc mat;
      mat.loc = m.loc;
      const Entry& nameEntry = m.require("name");
      mat.name = string(nameEntry);
      if (materialIds_.count(mat.name) > 0) {
        const FileLoc& first = scene_.materials[materialIds_.at(mat.name)].loc;
        fail(loc(nameEntry), "duplicate material " + shown(mat.name) + " (first defined at " +
                                 first.toString() + ")");
      }
      if (const Entry* e = m.find("ambient")) mat.ambient = color(*e);
      if (const Entry* e = m.find("diffuse")) mat.diffuse = color(*e);
      if (const Entry* e = m.find("checker")) mat.checker = checker(*e);
      if (const Entry* e = m.find("specular")) mat.specular = color(*e);
      if (const Entry* e = m.find("shininess")) mat.shininess = nonNegative(*e);
      if (const Entry* e = m.find("reflectance")) mat.reflectance = color(*e);
      if (const Entry* e = m.find("transmittance")) mat.transmittance = color(*e);
      if (const Entry* e = m.find("ior")) {
        mat.ior = number(*e);
        if (!(mat.ior >= 1.0f)) fail(loc(*e), "'ior' must be at least 1, found " + text(*e));
      }
      if (const Entry* e = m.find("fresnel")) mat.fresnel = boolean(*e);
      materialIds_.emplace(mat.name, static_cast<MaterialId>(scene_.materials.size()));
      scene_.materials.push_back(std::move(mat));
    }
  }

  CheckerDesc checker(const Entry& section) const {
    const Mapping m = mapping(section, "checker", kCheckerKeys);
    CheckerDesc c;
    if (const Entry* e = m.find("colors")) {
      if (!e->value.IsSequence() || e->value.size() != 2) {
        fail(loc(*e), "expected a list of 2 colours for 'colors', found " + describe(e->value));
      }
      c.colorA = color(e->value[0], itemLoc(e->value[0], loc(*e)), "colors");
      c.colorB = color(e->value[1], itemLoc(e->value[1], loc(*e)), "colors");
    }
    if (const Entry* e = m.find("scale")) c.scale = positive(*e);
    return c;
  }

  void readLights(const Entry& section) {
    for (const YAML::Node& item : list(section, "lights")) {
      const Mapping m = mapping(item, itemLoc(item, loc(section)), "light", kLightKeys);
      PointLightDesc light;
      light.loc = m.loc;
      light.position = vec3(m.require("position"));
      if (const Entry* e = m.find("intensity")) light.intensity = color(*e);
      if (const Entry* e = m.find("attenuation")) {
        const Vec3 a = vec3(e->value, loc(*e), e->key, /*nonNegative=*/true);
        if (a == Vec3(0.0f)) {
          fail(loc(*e),
               "'attenuation' [0, 0, 0] would make the light infinitely bright; at "
               "least one coefficient must be positive");
        }
        light.attenuation = Attenuation{a.x, a.y, a.z};
      }
      scene_.lights.push_back(light);
    }
  }

  // ---- objects ----------------------------------------------------------------------------

  void readObjects(const Entry& section) {
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
             "an object entry holds exactly one object, found '" + kinds.entries[0].key +
                 "' and '" + kinds.entries[1].key + "'; start each object with its own '-'");
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

  MaterialId material(const Mapping& m) {
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

  // The built-in material of objects that name none; added to the list only once it is used,
  // so a scene that names every material keeps exactly the materials it wrote.
  MaterialId defaultMaterial() {
    if (!defaultMaterial_) {
      MaterialDesc mat;
      mat.name = std::string(kDefaultMaterialName);
      mat.loc = FileLoc{path_};
      defaultMaterial_ = static_cast<MaterialId>(scene_.materials.size());
      scene_.materials.push_back(std::move(mat));
    }
    return *defaultMaterial_;
  }

  // Any shape of geometry/ShapeKinds.h, by the keys it declares (geometry/ShapeKeys.h).
  template <class Desc>
  void readShape(const Entry& object, std::vector<Desc>& shapes) {
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

  void readPlane(const Entry& object) {
    const Mapping m = mapping(object, "plane", kPlaneKeys);
    PlaneDesc p;
    p.loc = m.loc;
    p.point = vec3(m.require("point"));
    p.normal = direction(m.require("normal"));
    p.material = material(m);
    p.caustic = causticRole(m);
    scene_.planes.push_back(p);
  }

  // A cylinder is written as one but read as a cone of equal radii.
  void readCylinder(const Entry& object) {
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

  // Three points (or normals) written as [[x,y,z], [x,y,z], [x,y,z]].
  std::array<Vec3, 3> threeVectors(const Entry& e, std::string_view what) const {
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

  void readTriangle(const Entry& object) {
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

  void readMesh(const Entry& object) {
    const Mapping m = mapping(object, "mesh", kMeshKeys);
    const Entry& fileEntry = m.require("file");
    const std::string file = string(fileEntry);
    const std::filesystem::path resolved = resolve(file);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(resolved, ec)) {
      const bool exists = std::filesystem::exists(resolved, ec);
      fail(loc(fileEntry), "mesh file " + shown(file) +
                               (exists ? " is not a regular file" : " not found") +
                               " (looked for '" + resolved.string() + "')");
    }
    MeshDesc mesh = loadMeshFile(resolved.string(), loc(fileEntry), meshBudget_.remaining());
    meshBudget_.spend(meshBuildBytes(mesh.triangleCount(), mesh.positions.size()));
    if (mesh.triangleCount() == 0)
      fail(loc(fileEntry), "mesh file " + shown(file) + " has no triangles");
    if (mesh.source.empty()) mesh.source = resolved.string();
    if (const Entry* e = m.find("transform")) applyTransform(*e, mesh);
    mesh.loc = m.loc;
    mesh.material = material(m);
    mesh.caustic = causticRole(m);
    scene_.meshes.push_back(std::move(mesh));
  }

  // Bakes scale, then rotation about X, Y and Z (in that order), then translation into the
  // mesh. Normals take the inverse transpose of the linear part, R·S⁻¹, and are renormalised.
  void applyTransform(const Entry& section, MeshDesc& mesh) const {
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
};

std::vector<std::string> toStrings(KeyTable keys) {
  return {keys.begin(), keys.end()};
}

}  // namespace

SceneDescription parseYamlScene(const std::string& text, const std::string& path,
                                const MemoryLimit& limit) {
  return YamlSceneReader(path, limit).read(text);
}

const std::map<std::string, std::vector<std::string>>& yamlSceneKeys() {
  static const std::map<std::string, std::vector<std::string>> keys = {
      {"top level", toStrings(kTopLevelKeys)},
      {"camera", toStrings(kCameraKeys)},
      {"render", toStrings(kRenderKeys)},
      {"environment", toStrings(kEnvironmentKeys)},
      {"caustics", toStrings(kCausticsKeys)},
      {"cubemap", toStrings(kCubeMapKeys)},
      {"materials", toStrings(kMaterialKeys)},
      {"checker", toStrings(kCheckerKeys)},
      {"lights", toStrings(kLightKeys)},
      {"objects", toStrings(kObjectKinds)},
#define PRISM_SHAPE_KEYS(Shape, plural) \
  {std::string(Shape##Desc::kName), toStrings(kShapeKeys<Shape##Desc>)},
      PRISM_SHAPE_KINDS(PRISM_SHAPE_KEYS)
#undef PRISM_SHAPE_KEYS
          {"plane", toStrings(kPlaneKeys)},
      {"cylinder", toStrings(kCylinderKeys)},
      {"triangle", toStrings(kTriangleKeys)},
      {"mesh", toStrings(kMeshKeys)},
      {"transform", toStrings(kTransformKeys)},
  };
  return keys;
}

}  // namespace prism

// Prism's YAML scene format, read with yaml-cpp. docs/scene-format.md is the reference; the key
// tables here and in YamlSceneObjects.cpp are exactly what the parser accepts, and a test checks
// that each is documented.
//
// This file and YamlSceneObjects.cpp (the objects section) are the schema: which sections and
// keys exist, their types, defaults and limits; the reader they define is
// parse/YamlSceneReader.h. Reading and checking the YAML itself (positions, types, unknown keys)
// is parse/CheckedYaml.h; enumerated values and numeric limits come from scene/SettingNames.h
// and SettingLimits.h, which the command line shares.
#include "parse/YamlSceneParser.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <optional>
#include <string_view>
#include <utility>

#include "image/ImageIo.h"
#include "parse/PrintableText.h"
#include "parse/YamlSceneReader.h"
#include "scene/SceneValidation.h"
#include "util/Parallel.h"

namespace prism {
namespace {

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

std::vector<std::string> toStrings(KeyTable keys) {
  return {keys.begin(), keys.end()};
}

}  // namespace

YamlSceneReader::YamlSceneReader(const std::string& path, const MemoryLimit& limit)
    : CheckedYaml(path),
      path_(path),
      baseDir_(std::filesystem::path(path).parent_path()),
      meshBudget_(limit, "the meshes before this one") {}

SceneDescription YamlSceneReader::read(const std::string& text) {
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

std::filesystem::path YamlSceneReader::resolve(const std::string& file) const {
  const std::filesystem::path p(file);
  return p.is_absolute() ? p : baseDir_ / p;
}

SceneDescription YamlSceneReader::readScene(const YAML::Node& root) {
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

void YamlSceneReader::readCamera(const Entry& section) {
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

void YamlSceneReader::readRender(const Entry& section) {
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

void YamlSceneReader::readCaustics(const Entry& section) {
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
  if (const Entry* e = m.find("passes")) c.passes = static_cast<int>(integer(*e, limits::kPasses));
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

void YamlSceneReader::readEnvironment(const Entry& section) {
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

void YamlSceneReader::readMaterials(const Entry& section) {
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

CheckerDesc YamlSceneReader::checker(const Entry& section) const {
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

void YamlSceneReader::readLights(const Entry& section) {
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

SceneDescription parseYamlScene(const std::string& text, const std::string& path,
                                const MemoryLimit& limit) {
  return YamlSceneReader(path, limit).read(text);
}

const std::map<std::string, std::vector<std::string>>& yamlSceneKeys() {
  static const std::map<std::string, std::vector<std::string>> keys = [] {
    std::map<std::string, std::vector<std::string>> sections = {
        {"top level", toStrings(kTopLevelKeys)}, {"camera", toStrings(kCameraKeys)},
        {"render", toStrings(kRenderKeys)},      {"environment", toStrings(kEnvironmentKeys)},
        {"caustics", toStrings(kCausticsKeys)},  {"cubemap", toStrings(kCubeMapKeys)},
        {"materials", toStrings(kMaterialKeys)}, {"checker", toStrings(kCheckerKeys)},
        {"lights", toStrings(kLightKeys)},
    };
    addObjectKeys(sections);
    return sections;
  }();
  return keys;
}

}  // namespace prism

// Prism's YAML scene format, read with yaml-cpp. docs/scene-format.md is the reference; the key
// tables below are exactly what the parser accepts, and a test checks that each is documented.
//
// yaml-cpp only builds the node tree; every value is checked here so that a mistake is reported
// at its own line and column with what was expected and what was found. The parser never uses
// yaml-cpp's as<T>() conversions: their errors do not say which key was wrong.
#include "parse/YamlSceneParser.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <map>
#include <span>
#include <sstream>
#include <string_view>
#include <utility>

#include "image/ImageIo.h"
#include "parse/ObjLoader.h"
#include "parse/PrintableText.h"
#include "scene/MeshBudget.h"

namespace prism {
namespace {

using KeyTable = std::span<const std::string_view>;

constexpr std::string_view kTopLevelKeys[] = {"camera",  "render",      "background",
                                              "ambient", "environment", "materials",
                                              "lights",  "objects",     "caustics"};
constexpr std::string_view kCameraKeys[] = {"projection", "position", "look_at", "up",
                                            "fov",        "width",    "near"};
constexpr std::string_view kRenderKeys[] = {"width",     "height",           "samples",
                                            "max_depth", "min_contribution", "seed",
                                            "exposure",  "triangle_test"};
constexpr std::string_view kCausticsKeys[] = {
    "method",    "photons",        "gather",          "max_radius",
    "filter",    "max_bounces",    "progressive",     "passes",
    "alpha",     "radius",         "time_budget",     "map_resolution",
    "map_steps", "map_blur_sigma", "map_blur_radius", "map_paths"};
constexpr std::string_view kEnvironmentKeys[] = {"cubemap", "scale"};
// In the OpenGL cube-map order of CubeMapDesc::faces: +X, -X, +Y, -Y, +Z, -Z.
constexpr std::string_view kCubeMapKeys[] = {"px", "nx", "py", "ny", "pz", "nz"};
constexpr std::string_view kMaterialKeys[] = {
    "name",      "ambient",     "diffuse",       "checker", "specular",
    "shininess", "reflectance", "transmittance", "ior",     "fresnel"};
constexpr std::string_view kCheckerKeys[] = {"colors", "scale"};
constexpr std::string_view kLightKeys[] = {"position", "intensity", "attenuation"};
constexpr std::string_view kObjectKinds[] = {"sphere",   "plane",    "cone",
                                             "cylinder", "triangle", "mesh"};
constexpr std::string_view kSphereKeys[] = {"center", "radius", "material", "caustic"};
constexpr std::string_view kPlaneKeys[] = {"point", "normal", "material", "caustic"};
constexpr std::string_view kConeKeys[] = {"base",        "base_radius", "apex",
                                          "apex_radius", "material",    "caustic"};
constexpr std::string_view kCylinderKeys[] = {"base", "apex", "radius", "material", "caustic"};
constexpr std::string_view kTriangleKeys[] = {"vertices", "normals", "material", "caustic"};
constexpr std::string_view kMeshKeys[] = {"file", "material", "transform", "caustic"};
constexpr std::string_view kTransformKeys[] = {"scale", "rotate", "translate"};

constexpr std::pair<std::string_view, Projection> kProjections[] = {
    {"perspective", Projection::Perspective}, {"orthographic", Projection::Orthographic}};
constexpr std::pair<std::string_view, TriangleTest> kTriangleTests[] = {
    {"moller-trumbore", TriangleTest::MollerTrumbore},
    {"plane-inside", TriangleTest::PlaneThenInside}};
constexpr std::pair<std::string_view, CausticMethod> kCausticMethods[] = {
    {"none", CausticMethod::None},
    {"photon_map", CausticMethod::PhotonMap},
    {"caustic_map", CausticMethod::CausticMap}};
constexpr std::pair<std::string_view, CausticMapPaths> kCausticMapPaths[] = {
    {"front_face", CausticMapPaths::FrontFace}, {"traced", CausticMapPaths::Traced}};
constexpr std::pair<std::string_view, PhotonFilter> kPhotonFilters[] = {
    {"box", PhotonFilter::Box},
    {"cone", PhotonFilter::Cone},
    {"epanechnikov", PhotonFilter::Epanechnikov}};
constexpr std::pair<std::string_view, CausticRole> kCausticRoles[] = {
    {"auto", CausticRole::Auto},
    {"cast", CausticRole::Cast},
    {"receive", CausticRole::Receive},
    {"both", CausticRole::Both},
    {"off", CausticRole::Off}};

// Deeper recursion than this risks the tracer's stack and never changes an image visibly.
constexpr int64_t kMaxDepthLimit = 256;
constexpr std::string_view kDefaultMaterialName = "default";

std::string joined(KeyTable keys, std::string_view separator = ", ") {
  std::string out;
  for (size_t i = 0; i < keys.size(); ++i) {
    if (i > 0) out += separator;
    out += keys[i];
  }
  return out;
}

// A scalar as it appears in an error message: quoted, printable, and short.
std::string shown(std::string_view text) {
  return "'" + printableExcerpt(text, 40) + "'";
}

// What a node holds, for "found ..." in messages. Never walks into the node: aliases can make
// a YAML tree cyclic.
std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Null:
      return "nothing";
    case YAML::NodeType::Scalar:
      return (node.Tag() == "!" ? "the quoted string " : "") + shown(node.Scalar());
    case YAML::NodeType::Sequence:
      return "a list of " + std::to_string(node.size()) + (node.size() == 1 ? " item" : " items");
    case YAML::NodeType::Map:
      return "a mapping";
    case YAML::NodeType::Undefined:
      break;
  }
  return "an undefined value";
}

bool isQuoted(const YAML::Node& node) {
  return node.Tag() == "!";
}

enum class NumberStatus { Ok, NotANumber, NotFinite, OutOfRange };

// YAML 1.2 core-schema floats (plus the integers they include). .inf and .nan are recognised
// so they can be refused as "not finite" rather than "not a number".
NumberStatus parseNumber(std::string_view text, double& value) {
  std::string_view body = text;
  if (!body.empty() && (body.front() == '+' || body.front() == '-')) body.remove_prefix(1);
  if (body == ".inf" || body == ".Inf" || body == ".INF" || body == ".nan" || body == ".NaN" ||
      body == ".NAN") {
    return NumberStatus::NotFinite;
  }
  if (body.empty() ||
      !(std::isdigit(static_cast<unsigned char>(body.front())) || body.front() == '.')) {
    return NumberStatus::NotANumber;
  }
  const char* first = text.data() + (text.front() == '+' ? 1 : 0);
  const char* last = text.data() + text.size();
  const auto [end, error] = std::from_chars(first, last, value, std::chars_format::general);
  if (end != last) return NumberStatus::NotANumber;
  if (error == std::errc::result_out_of_range) return NumberStatus::OutOfRange;
  if (error != std::errc()) return NumberStatus::NotANumber;
  if (!std::isfinite(value)) return NumberStatus::NotFinite;
  if (std::abs(value) > std::numeric_limits<float>::max()) return NumberStatus::OutOfRange;
  return NumberStatus::Ok;
}

// One key: value pair of a mapping. The key node is kept because an empty value has no useful
// position of its own (yaml-cpp marks it where the next token starts).
struct Entry {
  std::string key;
  YAML::Node keyNode;
  YAML::Node value;
};

// A mapping whose keys have been checked against a table: no unknown and no duplicate keys.
struct Mapping {
  std::string what;  // "sphere", "camera", ...: names it in "sphere needs 'radius'"
  FileLoc loc;
  std::vector<Entry> entries;

  const Entry* find(std::string_view key) const {
    for (const Entry& e : entries) {
      if (e.key == key) return &e;
    }
    return nullptr;
  }

  const Entry& require(std::string_view key) const {
    if (const Entry* e = find(key)) return *e;
    throw SceneError(loc, what + " needs '" + std::string(key) + "'");
  }
};

// Sees where each YAML document starts, and nothing else.
class DocumentStarts : public YAML::EventHandler {
 public:
  std::vector<YAML::Mark> starts;

  void OnDocumentStart(const YAML::Mark& mark) override { starts.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

class YamlSceneReader {
 public:
  YamlSceneReader(const std::string& path, const MemoryLimit& limit)
      : path_(path), baseDir_(std::filesystem::path(path).parent_path()), limit_(limit) {}

  SceneDescription read(const std::string& text) {
    YAML::Node root;
    try {
      checkSingleDocument(text);
      root = YAML::Load(text);
    } catch (const YAML::Exception& e) {
      throw SceneError(loc(e.mark), "invalid YAML: " + printableExcerpt(e.msg, 200));
    }
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
  MemoryLimit limit_;  // less what the meshes read so far need
  SceneDescription scene_;
  std::map<std::string, MaterialId, std::less<>> materialIds_;
  std::optional<MaterialId> defaultMaterial_;

  // A scene is one YAML document. This also guards against a yaml-cpp 0.7 bug: on some
  // malformed input (a lone ',', jbeder/yaml-cpp#1040) its parser reports an empty document
  // again and again without consuming anything, and YAML::LoadAll allocates until memory runs
  // out. So documents are counted here, two at most, and one that makes no progress is a
  // syntax error at the token that stopped it.
  void checkSingleDocument(const std::string& text) const {
    std::istringstream stream(text);
    YAML::Parser parser(stream);
    DocumentStarts documents;
    if (!parser.HandleNextDocument(documents) || !parser.HandleNextDocument(documents)) return;
    if (documents.starts.size() != 2) {
      throw SceneError(FileLoc{path_}, "expected one YAML document, found more");
    }
    const YAML::Mark& first = documents.starts.front();
    const YAML::Mark& second = documents.starts.back();
    if (second.pos == first.pos) {
      const size_t pos = std::min(static_cast<size_t>(std::max(second.pos, 0)), text.size());
      throw SceneError(loc(second),
                       "invalid YAML: unexpected " + shown(std::string_view(text).substr(pos, 1)));
    }
    throw SceneError(loc(second), "expected one YAML document, found more (a second starts here)");
  }

  // ---- positions and messages ------------------------------------------------------------

  FileLoc loc(const YAML::Mark& mark) const {
    if (mark.is_null() || mark.line < 0) return FileLoc{path_};
    return FileLoc{path_, mark.line + 1, mark.column + 1};
  }
  FileLoc loc(const YAML::Node& node) const { return loc(node.Mark()); }
  FileLoc loc(const Entry& e) const { return e.value.IsNull() ? loc(e.keyNode) : loc(e.value); }
  // A list item's own position, or the list's when the item is empty.
  FileLoc itemLoc(const YAML::Node& item, const FileLoc& listLoc) const {
    return item.IsNull() ? listLoc : loc(item);
  }

  [[noreturn]] void fail(const FileLoc& where, const std::string& message) const {
    throw SceneError(where, message);
  }

  // ---- structure --------------------------------------------------------------------------

  // Checks that node is a mapping with only the keys in table, each once. An empty value (as
  // in "camera:" with nothing under it) is an empty mapping: everything takes its default.
  Mapping mapping(const YAML::Node& node, const FileLoc& where, std::string_view what,
                  KeyTable table, std::string_view keyNoun = "key") const {
    Mapping m{std::string(what), where, {}};
    if (node.IsNull()) return m;
    if (!node.IsMap()) {
      fail(where, "expected a mapping of " + std::string(what) + " keys (" + joined(table) +
                      "), found " + describe(node));
    }
    for (auto it = node.begin(); it != node.end(); ++it) {
      const YAML::Node key = it->first;  // a copy: it-> yields a temporary
      if (!key.IsScalar()) fail(loc(key), "expected a key name, found " + describe(key));
      const std::string& name = key.Scalar();
      if (const Entry* earlier = m.find(name)) {
        const FileLoc first = loc(earlier->keyNode);
        fail(loc(key), "duplicate key " + shown(name) + " (first given at " +
                           std::to_string(first.line) + ":" + std::to_string(first.column) + ")");
      }
      bool known = false;
      for (std::string_view k : table) known = known || k == name;
      if (!known) {
        fail(loc(key), "unknown " + std::string(what) + " " + std::string(keyNoun) + " " +
                           shown(name) + " (expected one of: " + joined(table) + ")");
      }
      m.entries.push_back(Entry{name, key, it->second});
    }
    return m;
  }

  Mapping mapping(const Entry& e, std::string_view what, KeyTable table) const {
    return mapping(e.value, loc(e), what, table);
  }

  // The items of a list section; an empty value is an empty list.
  std::vector<YAML::Node> list(const Entry& e, std::string_view itemsName) const {
    std::vector<YAML::Node> items;
    if (e.value.IsNull()) return items;
    if (!e.value.IsSequence()) {
      fail(loc(e), "expected a list of " + std::string(itemsName) + " for '" + e.key + "', found " +
                       describe(e.value));
    }
    for (const YAML::Node& item : e.value) items.push_back(item);
    return items;
  }

  // ---- values -----------------------------------------------------------------------------

  float number(const YAML::Node& node, const FileLoc& where, std::string_view name) const {
    const std::string forName = " for '" + std::string(name) + "'";
    if (!node.IsScalar() || isQuoted(node)) {
      fail(where, "expected a number" + forName + ", found " + describe(node));
    }
    double value = 0.0;
    switch (parseNumber(node.Scalar(), value)) {
      case NumberStatus::Ok:
        return static_cast<float>(value);
      case NumberStatus::NotANumber:
        fail(where, "expected a number" + forName + ", found " + describe(node));
      case NumberStatus::NotFinite:
        fail(where, "'" + std::string(name) + "' must be finite, found " + describe(node));
      case NumberStatus::OutOfRange:
        fail(where, "'" + std::string(name) + "' is out of range for a 32-bit float, found " +
                        describe(node));
    }
    fail(where, "expected a number" + forName);
  }

  float number(const Entry& e) const { return number(e.value, loc(e), e.key); }

  float positive(const Entry& e) const {
    const float v = number(e);
    if (!(v > 0.0f)) fail(loc(e), "'" + e.key + "' must be greater than 0, found " + text(e));
    return v;
  }

  float nonNegative(const Entry& e) const {
    const float v = number(e);
    if (v < 0.0f) fail(loc(e), "'" + e.key + "' must not be negative, found " + text(e));
    return v;
  }

  static std::string text(const Entry& e) { return e.value.Scalar(); }

  int64_t integer(const Entry& e, int64_t min, int64_t max) const {
    const YAML::Node& node = e.value;
    if (!node.IsScalar() || isQuoted(node)) {
      fail(loc(e), "expected an integer for '" + e.key + "', found " + describe(node));
    }
    const std::string& s = node.Scalar();
    const char* first = s.data() + (!s.empty() && s.front() == '+' ? 1 : 0);
    const char* last = s.data() + s.size();
    int64_t value = 0;
    const auto [end, error] = std::from_chars(first, last, value);
    if (end != last || error == std::errc::invalid_argument) {
      fail(loc(e), "expected an integer for '" + e.key + "', found " + describe(node));
    }
    if (error == std::errc::result_out_of_range || value > max) {
      fail(loc(e), "'" + e.key + "' must be at most " + std::to_string(max) + ", found " + s);
    }
    if (value < min) {
      fail(loc(e), "'" + e.key + "' must be at least " + std::to_string(min) + ", found " + s);
    }
    return value;
  }

  uint64_t unsignedInteger(const Entry& e) const {
    const YAML::Node& node = e.value;
    const std::string s = node.IsScalar() ? node.Scalar() : std::string();
    if (!node.IsScalar() || isQuoted(node)) {
      fail(loc(e), "expected an integer for '" + e.key + "', found " + describe(node));
    }
    if (!s.empty() && s.front() == '-') {
      fail(loc(e), "'" + e.key + "' must not be negative, found " + s);
    }
    const char* first = s.data() + (!s.empty() && s.front() == '+' ? 1 : 0);
    const char* last = s.data() + s.size();
    uint64_t value = 0;
    const auto [end, error] = std::from_chars(first, last, value);
    if (end != last || error == std::errc::invalid_argument) {
      fail(loc(e), "expected an integer for '" + e.key + "', found " + describe(node));
    }
    if (error == std::errc::result_out_of_range) {
      fail(loc(e), "'" + e.key + "' must be at most " +
                       std::to_string(std::numeric_limits<uint64_t>::max()) + ", found " + s);
    }
    return value;
  }

  bool boolean(const Entry& e) const {
    const YAML::Node& node = e.value;
    if (node.IsScalar() && !isQuoted(node)) {
      const std::string& s = node.Scalar();
      if (s == "true" || s == "True" || s == "TRUE") return true;
      if (s == "false" || s == "False" || s == "FALSE") return false;
    }
    fail(loc(e), "expected true or false for '" + e.key + "', found " + describe(node));
  }

  std::string string(const Entry& e) const {
    const YAML::Node& node = e.value;
    if (!node.IsScalar()) {
      fail(loc(e), "expected a name for '" + e.key + "', found " + describe(node));
    }
    if (node.Scalar().empty()) fail(loc(e), "'" + e.key + "' must not be empty");
    return node.Scalar();
  }

  template <typename T, size_t N>
  T choice(const Entry& e, const std::pair<std::string_view, T> (&choices)[N]) const {
    std::string options;
    for (size_t i = 0; i < N; ++i) {
      if (i > 0) options += i + 1 == N ? " or " : ", ";
      options += choices[i].first;
    }
    if (!e.value.IsScalar()) {
      fail(loc(e), "expected " + options + " for '" + e.key + "', found " + describe(e.value));
    }
    for (const auto& [name, value] : choices) {
      if (e.value.Scalar() == name) return value;
    }
    fail(loc(e),
         "unknown " + e.key + " " + shown(e.value.Scalar()) + " (expected " + options + ")");
  }

  // Three numbers; with nonNegative, a negative component is reported at its own position.
  Vec3 vec3(const YAML::Node& node, const FileLoc& where, std::string_view name,
            bool nonNegative = false) const {
    if (!node.IsSequence() || node.size() != 3) {
      fail(where,
           "expected a list of 3 numbers for '" + std::string(name) + "', found " + describe(node));
    }
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
      const YAML::Node item = node[i];
      const FileLoc itemAt = itemLoc(item, where);
      v[i] = number(item, itemAt, name);
      if (nonNegative && v[i] < 0.0f) {
        fail(itemAt, "'" + std::string(name) + "' must not be negative, found " + item.Scalar());
      }
    }
    return v;
  }

  Vec3 vec3(const Entry& e) const { return vec3(e.value, loc(e), e.key); }

  Vec3 direction(const Entry& e) const {
    const Vec3 v = vec3(e);
    if (v == Vec3(0.0f)) fail(loc(e), "'" + e.key + "' must not be the zero vector");
    return glm::normalize(v);
  }

  // A colour is one number s (meaning [s, s, s]) or [r, g, b]; components are never negative.
  Color color(const YAML::Node& node, const FileLoc& where, std::string_view name) const {
    if (node.IsScalar()) {
      const float s = number(node, where, name);
      if (s < 0.0f) {
        fail(where, "'" + std::string(name) + "' must not be negative, found " + node.Scalar());
      }
      return Color(s);
    }
    if (!node.IsSequence() || node.size() != 3) {
      fail(where, "expected a colour (a number or a list of 3 numbers) for '" + std::string(name) +
                      "', found " + describe(node));
    }
    return vec3(node, where, name, /*nonNegative=*/true);
  }

  Color color(const Entry& e) const { return color(e.value, loc(e), e.key); }

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
    return std::move(scene_);
  }

  void readCamera(const Entry& section) {
    const Mapping m = mapping(section, "camera", kCameraKeys);
    CameraDesc& cam = scene_.camera;
    cam.loc = m.loc;
    if (const Entry* e = m.find("projection")) cam.projection = choice(*e, kProjections);
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
    constexpr int64_t kIntMax = std::numeric_limits<int>::max();
    if (const Entry* e = m.find("width")) r.width = static_cast<int>(integer(*e, 1, kIntMax));
    if (const Entry* e = m.find("height")) r.height = static_cast<int>(integer(*e, 1, kIntMax));
    if (const Entry* e = m.find("samples")) {
      r.samplesPerPixel = static_cast<int>(integer(*e, 1, kIntMax));
    }
    if (const Entry* e = m.find("max_depth")) {
      r.maxDepth = static_cast<int>(integer(*e, 0, kMaxDepthLimit));
    }
    if (const Entry* e = m.find("min_contribution")) r.minContribution = nonNegative(*e);
    if (const Entry* e = m.find("seed")) r.seed = unsignedInteger(*e);
    if (const Entry* e = m.find("exposure")) r.exposure = positive(*e);
    if (const Entry* e = m.find("triangle_test")) r.triangleTest = choice(*e, kTriangleTests);
  }

  void readCaustics(const Entry& section) {
    const Mapping m = mapping(section, "caustics", kCausticsKeys);
    CausticSettings& c = scene_.caustics;
    constexpr int64_t kIntMax = std::numeric_limits<int>::max();
    if (const Entry* e = m.find("method")) c.method = choice(*e, kCausticMethods);
    if (const Entry* e = m.find("photons")) {
      c.photons = unsignedInteger(*e);
      if (c.photons == 0) fail(loc(*e), "'photons' must be at least 1");
    }
    if (const Entry* e = m.find("gather")) c.gather = static_cast<int>(integer(*e, 1, 100000));
    if (const Entry* e = m.find("max_radius")) c.maxRadius = nonNegative(*e);
    if (const Entry* e = m.find("filter")) c.filter = choice(*e, kPhotonFilters);
    if (const Entry* e = m.find("max_bounces")) {
      c.maxBounces = static_cast<int>(integer(*e, 1, kMaxDepthLimit));
    }
    if (const Entry* e = m.find("progressive")) c.progressive = boolean(*e);
    if (const Entry* e = m.find("passes")) c.passes = static_cast<int>(integer(*e, 1, kIntMax));
    if (const Entry* e = m.find("alpha")) {
      c.alpha = number(*e);
      if (!(c.alpha > 0.0f && c.alpha < 1.0f)) {
        fail(loc(*e), "'alpha' must lie strictly between 0 and 1, found " + text(*e));
      }
    }
    if (const Entry* e = m.find("radius")) c.radius = nonNegative(*e);
    if (const Entry* e = m.find("time_budget")) c.timeBudgetSeconds = nonNegative(*e);
    if (const Entry* e = m.find("map_resolution")) {
      c.mapResolution =
          static_cast<int>(integer(*e, kMinCausticMapResolution, kMaxCausticMapResolution));
    }
    if (const Entry* e = m.find("map_steps")) {
      c.mapSteps = static_cast<int>(integer(*e, 1, kMaxCausticMapSteps));
    }
    if (const Entry* e = m.find("map_blur_sigma")) c.mapBlurSigma = nonNegative(*e);
    if (const Entry* e = m.find("map_blur_radius")) {
      c.mapBlurRadius = static_cast<int>(integer(*e, 0, kMaxCausticMapBlurRadius));
    }
    if (const Entry* e = m.find("map_paths")) c.mapPaths = choice(*e, kCausticMapPaths);
  }

  CausticRole causticRole(const Mapping& m) const {
    const Entry* e = m.find("caustic");
    return e ? choice(*e, kCausticRoles) : CausticRole::Auto;
  }

  void readEnvironment(const Entry& section) {
    const Mapping m = mapping(section, "environment", kEnvironmentKeys);
    CubeMapDesc cube;
    if (const Entry* e = m.find("scale")) cube.scale = nonNegative(*e);
    const Mapping faces = mapping(m.require("cubemap"), "cubemap", kCubeMapKeys);
    // Every face must be named before any is read, so a missing key is reported as such.
    for (std::string_view key : kCubeMapKeys) faces.require(key);
    for (size_t i = 0; i < std::size(kCubeMapKeys); ++i) {
      const Entry& face = faces.require(kCubeMapKeys[i]);
      cube.paths[i] = string(face);
      try {
        cube.faces[i] = readImage(resolve(cube.paths[i]).string());
      } catch (const std::exception& error) {
        fail(loc(face), "cube-map face '" + face.key + "': " + error.what());
      }
      const ImageRgb& image = cube.faces[i];
      if (image.width <= 0 || image.width != image.height) {
        fail(loc(face), "cube-map face '" + face.key + "' is " + std::to_string(image.width) + "x" +
                            std::to_string(image.height) + "; faces must be square");
      }
      if (i > 0 && image.width != cube.faces[0].width) {
        fail(loc(face), "cube-map face '" + face.key + "' is " + std::to_string(image.width) +
                            " pixels wide but 'px' is " + std::to_string(cube.faces[0].width) +
                            "; all faces must be the same size");
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
      if (object.key == "sphere") readSphere(object);
      if (object.key == "plane") readPlane(object);
      if (object.key == "cone") readCone(object);
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

  void readSphere(const Entry& object) {
    const Mapping m = mapping(object, "sphere", kSphereKeys);
    SphereDesc s;
    s.loc = m.loc;
    s.center = vec3(m.require("center"));
    s.radius = positive(m.require("radius"));
    s.material = material(m);
    s.caustic = causticRole(m);
    scene_.spheres.push_back(s);
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

  // base and apex must differ or the cone has no axis.
  void checkAxis(const Mapping& m, const ConeDesc& c) const {
    if (c.base == c.apex) fail(loc(m.require("apex")), "'apex' must differ from 'base'");
  }

  void readCone(const Entry& object) {
    const Mapping m = mapping(object, "cone", kConeKeys);
    ConeDesc c;
    c.loc = m.loc;
    c.base = vec3(m.require("base"));
    c.apex = vec3(m.require("apex"));
    checkAxis(m, c);
    c.baseRadius = nonNegative(m.require("base_radius"));
    c.apexRadius = 0.0f;
    if (const Entry* e = m.find("apex_radius")) c.apexRadius = nonNegative(*e);
    if (c.baseRadius == 0.0f && c.apexRadius == 0.0f) {
      fail(loc(m.require("base_radius")), "a cone needs 'base_radius' or 'apex_radius' above 0");
    }
    c.material = material(m);
    c.caustic = causticRole(m);
    scene_.cones.push_back(c);
  }

  void readCylinder(const Entry& object) {
    const Mapping m = mapping(object, "cylinder", kCylinderKeys);
    ConeDesc c;
    c.loc = m.loc;
    c.base = vec3(m.require("base"));
    c.apex = vec3(m.require("apex"));
    checkAxis(m, c);
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
    MeshDesc mesh = loadObjMesh(resolved.string(), loc(fileEntry), limit_);
    const uint64_t meshBytes = meshBuildBytes(mesh.triangleCount(), mesh.positions.size());
    limit_.bytes -= std::min(limit_.bytes, meshBytes);
    if (limit_.source.find("less the meshes") == std::string::npos)
      limit_.source += ", less the meshes before this one";
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
      {"top level", toStrings(kTopLevelKeys)},  {"camera", toStrings(kCameraKeys)},
      {"render", toStrings(kRenderKeys)},       {"environment", toStrings(kEnvironmentKeys)},
      {"caustics", toStrings(kCausticsKeys)},   {"cubemap", toStrings(kCubeMapKeys)},
      {"materials", toStrings(kMaterialKeys)},  {"checker", toStrings(kCheckerKeys)},
      {"lights", toStrings(kLightKeys)},        {"objects", toStrings(kObjectKinds)},
      {"sphere", toStrings(kSphereKeys)},       {"plane", toStrings(kPlaneKeys)},
      {"cone", toStrings(kConeKeys)},           {"cylinder", toStrings(kCylinderKeys)},
      {"triangle", toStrings(kTriangleKeys)},   {"mesh", toStrings(kMeshKeys)},
      {"transform", toStrings(kTransformKeys)},
  };
  return keys;
}

}  // namespace prism

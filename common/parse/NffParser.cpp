// Eric Haines' Neutral File Format, as documented in NFF.TXT of the Standard Procedural Databases
// (SPD 3.14). Quotes marked "spec" below are from that text.
//
// Statements: v (with from/at/up/angle/hither/resolution), b, l, f, c, s, p, pp, and # comments.
// Numbers may be spread over lines however a writer likes (the SPD generators put a whole cone on
// one line although the spec shows two); the only place a line break would matter, the optional
// colour of a light, is recognised by whether the next word is a number instead.
//
// Mapping to Prism's units (Prism's documented SPD convention):
// - n lights: each has intensity pi * sqrt(n) / (2n) W/sr times its colour, with no distance
//   falloff. SPD suggests sqrt(n)/(2n) for NFF's unitless intensity; with Lambertian albedo/pi
//   the factor pi makes a surface facing a light reflect Kd * rgb * sqrt(n)/(2n), as in SPD.
// - f r g b Kd Ks Shine T ior: diffuse = Kd * rgb, Phong specular = Ks / pi, shininess = Shine,
//   mirror reflectance = Ks, transmittance = T, no Fresnel split (NFF has none).
// - Render settings: 512 x 512 unless 'resolution' says otherwise, depth 5, one sample a pixel
//   (SPD's rules for timing runs), no ambient light.
#include "parse/NffParser.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>

#include "parse/PolygonTriangulator.h"
#include "parse/PrintableText.h"
#include "scene/SceneValidation.h"
#include "scene/SettingLimits.h"

namespace prism {

namespace {

struct Token {
  std::string_view text;
  int line = 0;    // 1-based
  int column = 0;  // 1-based, in bytes
};

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// Splits NFF text into words separated by white space, each with its line and column. Spec: "As
// soon as a '#' character is detected, the rest of the line is considered a comment."
class NffTokenizer {
 public:
  explicit NffTokenizer(std::string_view text) : text_(text) {}

  const std::optional<Token>& peek() {
    if (!peeked_) peeked_ = scan();
    return *peeked_;
  }

  std::optional<Token> next() {
    std::optional<Token> token = peek();
    peeked_.reset();
    return token;
  }

 private:
  std::optional<Token> scan() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') {
        ++pos_;
        ++line_;
        column_ = 1;
      } else if (isSpace(c)) {
        ++pos_;
        ++column_;
      } else if (c == '#') {
        const size_t end = text_.find('\n', pos_);
        pos_ = end == std::string_view::npos ? text_.size() : end;
      } else {
        break;
      }
    }
    if (pos_ == text_.size()) return std::nullopt;
    Token token{{}, line_, column_};
    const size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n' && text_[pos_] != '#' &&
           !isSpace(text_[pos_])) {
      ++pos_;
      ++column_;
    }
    token.text = text_.substr(start, pos_ - start);
    return token;
  }

  std::string_view text_;
  size_t pos_ = 0;
  int line_ = 1;
  int column_ = 1;
  std::optional<std::optional<Token>> peeked_;
};

enum class NumberStatus { Ok, NotANumber, OutOfRange, NotFinite };

NumberStatus parseFloat(std::string_view word, float& value) {
  const char* first = word.data();
  const char* last = word.data() + word.size();
  if (first != last && *first == '+') ++first;  // from_chars rejects a leading '+'
  double parsed = 0.0;
  const auto [end, error] = std::from_chars(first, last, parsed);
  if (error == std::errc::result_out_of_range) return NumberStatus::OutOfRange;
  if (error != std::errc() || end != last) return NumberStatus::NotANumber;
  if (std::isnan(parsed) || std::isinf(parsed)) return NumberStatus::NotFinite;
  if (std::fabs(parsed) > std::numeric_limits<float>::max()) return NumberStatus::OutOfRange;
  value = static_cast<float>(parsed);
  return NumberStatus::Ok;
}

bool isViewKeyword(std::string_view word) {
  return word == "from" || word == "at" || word == "up" || word == "angle" || word == "hither" ||
         word == "resolution";
}

struct Number {
  float value = 0.0f;
  Token token;
};

class NffParser {
 public:
  NffParser(std::string_view text, const std::string& path) : tokens_(text), path_(path) {}

  SceneDescription parse() {
    scene_.sourcePath = path_;
    scene_.render.width = 512;
    scene_.render.height = 512;
    scene_.render.maxDepth = 5;
    scene_.render.samplesPerPixel = 1;
    scene_.ambientLight = Color(0.0f);
    while (std::optional<Token> command = tokens_.next()) parseStatement(*command);
    finishLights();
    try {
      validate(scene_);  // each statement checks its own values: this is the backstop
    } catch (const SettingError& e) {
      throw SceneError(FileLoc{path_}, e.what());
    }
    return std::move(scene_);
  }

 private:
  FileLoc loc(const Token& token) const { return FileLoc{path_, token.line, token.column}; }

  [[noreturn]] void fail(const Token& token, const std::string& message) const {
    throw SceneError(loc(token), message);
  }

  void parseStatement(const Token& command) {
    const std::string_view word = command.text;
    if (word == "v") {
      parseView(command);
    } else if (word == "b") {
      scene_.background = readColor(command, "the background colour");
    } else if (word == "l") {
      parseLight(command);
    } else if (word == "f") {
      parseMaterial(command);
    } else if (word == "c") {
      parseCone(command);
    } else if (word == "s") {
      parseSphere(command);
    } else if (word == "p") {
      parsePolygon(command, false);
    } else if (word == "pp") {
      parsePolygon(command, true);
    } else if (isViewKeyword(word)) {
      fail(command, "'" + std::string(word) + "' belongs in a viewpoint block (after a 'v' line)");
    } else {
      float unused = 0.0f;
      if (parseFloat(word, unused) == NumberStatus::Ok) {
        fail(command, "unexpected number '" + printableExcerpt(word) +
                          "' where an NFF command should start (too many numbers before it?)");
      }
      fail(command, "unknown NFF command '" + printableExcerpt(word) + "'");
    }
  }

  // ---- reading words ----

  // thing names what is being read, for the message when the file ends in the middle of it; the
  // error points at the command that started it.
  Token nextWord(const Token& command, const char* thing) {
    std::optional<Token> token = tokens_.next();
    if (!token) fail(command, std::string("unexpected end of file while reading ") + thing);
    return *token;
  }

  Number readNumber(const Token& command, const char* thing) {
    const Token token = nextWord(command, thing);
    Number number{0.0f, token};
    switch (parseFloat(token.text, number.value)) {
      case NumberStatus::Ok:
        return number;
      case NumberStatus::NotANumber:
        fail(token, "expected a number but found '" + printableExcerpt(token.text) +
                        "' while reading " + thing);
      case NumberStatus::OutOfRange:
        fail(token, "number '" + printableExcerpt(token.text) + "' is out of range");
      case NumberStatus::NotFinite:
        fail(token,
             "non-finite number '" + printableExcerpt(token.text) + "' while reading " + thing);
    }
    return number;
  }

  float readFloat(const Token& command, const char* thing) {
    return readNumber(command, thing).value;
  }

  long long readInteger(const Token& command, const char* thing, Token* where = nullptr) {
    const Token token = nextWord(command, thing);
    if (where) *where = token;
    const char* first = token.text.data();
    const char* last = first + token.text.size();
    if (first != last && *first == '+') ++first;
    long long value = 0;
    const auto [end, error] = std::from_chars(first, last, value);
    if (error == std::errc::result_out_of_range) {
      fail(token, "number '" + printableExcerpt(token.text) + "' is out of range");
    }
    if (error != std::errc() || end != last) {
      fail(token, "expected a whole number but found '" + printableExcerpt(token.text) +
                      "' while reading " + thing);
    }
    return value;
  }

  Vec3 readVec3(const Token& command, const char* thing) {
    Vec3 v;
    for (int k = 0; k < 3; ++k) v[k] = readFloat(command, thing);
    return v;
  }

  Color readColor(const Token& command, const char* thing) {
    Color color;
    for (int k = 0; k < 3; ++k) color[k] = readNonNegative(command, thing, "colour components");
    return color;
  }

  float readNonNegative(const Token& command, const char* thing, const char* what) {
    const Number number = readNumber(command, thing);
    if (number.value < 0.0f) {
      fail(number.token, std::string(what) + " must not be negative (got " +
                             std::string(number.token.text) + ")");
    }
    return number.value;
  }

  bool nextIsNumber() {
    const std::optional<Token>& token = tokens_.peek();
    float unused = 0.0f;
    return token && parseFloat(token->text, unused) != NumberStatus::NotANumber;
  }

  // ---- statements ----

  // Spec: "v" then "from", "at", "up", "angle", "hither", "resolution" lines. The SPD reader
  // treats hither and resolution as optional; here every line is, in any order, and what is
  // missing keeps Prism's default.
  void parseView(const Token& command) {
    constexpr const char* kThing = "a viewpoint ('v')";
    CameraDesc& camera = scene_.camera;
    camera.projection = Projection::Perspective;
    camera.loc = loc(command);
    Token atToken = command;
    Token upToken = command;
    while (tokens_.peek() && isViewKeyword(tokens_.peek()->text)) {
      const Token keyword = *tokens_.next();
      const std::string_view word = keyword.text;
      if (word == "from") {
        camera.position = readVec3(keyword, kThing);
      } else if (word == "at") {
        atToken = keyword;
        camera.lookAt = readVec3(keyword, kThing);
      } else if (word == "up") {
        upToken = keyword;
        camera.up = readVec3(keyword, kThing);
      } else if (word == "angle") {
        // Spec: the angle runs "from the center of top pixel row to bottom pixel row"; Prism takes
        // it as the full vertical field of view, edge to edge (one pixel's difference).
        const Number angle = readNumber(keyword, kThing);
        if (!(angle.value > 0.0f && angle.value < 180.0f)) {
          fail(angle.token, "field of view must be between 0 and 180 degrees (got " +
                                std::string(angle.token.text) + ")");
        }
        camera.fovDegrees = angle.value;
      } else if (word == "hither") {
        camera.nearClip = readNonNegative(keyword, kThing, "hither distance");
      } else {  // resolution
        Token where;
        for (int* size : {&scene_.render.width, &scene_.render.height}) {
          const long long value = readInteger(keyword, kThing, &where);
          if (value <= 0) {
            fail(where, "resolution must be positive (got " + std::string(where.text) + ")");
          }
          if (value > limits::kWidth.max) {  // the same bound as the YAML render width
            fail(where, "resolution must be at most " + std::to_string(limits::kWidth.max) +
                            " (got " + std::string(where.text) + ")");
          }
          *size = static_cast<int>(value);
        }
      }
    }
    const Vec3 direction = camera.lookAt - camera.position;
    if (maxAbsComponent(direction) == 0.0f) {
      fail(atToken, "the 'at' point is the same as the 'from' point");
    }
    if (maxAbsComponent(glm::cross(direction, camera.up)) == 0.0f) {
      fail(upToken, "the 'up' vector is zero or parallel to the viewing direction");
    }
  }

  // Spec: "l X Y Z" with an optional "R G B" colour (white when absent). The intensity is set in
  // finishLights(), once the number of lights is known.
  void parseLight(const Token& command) {
    constexpr const char* kThing = "a light ('l')";
    PointLightDesc light;
    light.loc = loc(command);
    light.position = readVec3(command, kThing);
    light.intensity = nextIsNumber() ? readColor(command, kThing) : Color(1.0f);
    // NFF lights do not fall off with distance.
    light.attenuation = Attenuation{1.0f, 0.0f, 0.0f};
    scene_.lights.push_back(light);
  }

  void finishLights() {
    if (scene_.lights.empty()) return;
    const float n = static_cast<float>(scene_.lights.size());
    const float intensity = kPi * std::sqrt(n) / (2.0f * n);
    for (PointLightDesc& light : scene_.lights) light.intensity *= intensity;
  }

  // Spec: "f" red green blue Kd Ks Shine T index_of_refraction.
  void parseMaterial(const Token& command) {
    constexpr const char* kThing = "a material ('f')";
    const Color color = readColor(command, kThing);
    const float kd = readNonNegative(command, kThing, "Kd");
    const float ks = readNonNegative(command, kThing, "Ks");
    const float shine = readNonNegative(command, kThing, "Shine");
    const Number t = readNumber(command, kThing);
    if (!(t.value >= 0.0f && t.value <= 1.0f)) {
      // Spec: "T is transmittance (fraction of light passed per unit)".
      fail(t.token,
           "transmittance T must be between 0 and 1 (got " + std::string(t.token.text) + ")");
    }
    const Number ior = readNumber(command, kThing);
    if (ior.value < 0.0f) {
      fail(ior.token,
           "index of refraction must not be negative (got " + std::string(ior.token.text) + ")");
    }
    if (t.value > 0.0f && ior.value < 1.0f) {
      fail(ior.token, "index of refraction must be at least 1 for a transparent material (T = " +
                          std::string(t.token.text) + "), got " + std::string(ior.token.text));
    }

    MaterialDesc material;
    // Appended, not "f" + string: GCC 12 warns (-Wrestrict) about that form, wrongly.
    material.name = "f";
    material.name += std::to_string(scene_.materials.size() + 1);
    material.loc = loc(command);
    material.ambient = Color(0.0f);
    material.diffuse = kd * color;
    material.specular = Color(ks * kInvPi);
    material.shininess = shine;
    material.reflectance = Color(ks);
    material.transmittance = Color(t.value);
    // The SPD generators write "0 0" or "0 1" for opaque materials: the index of an object that
    // lets no light through is never used, so anything below 1 is stored as 1 (vacuum).
    material.ior = t.value > 0.0f ? ior.value : std::max(ior.value, 1.0f);
    material.fresnel = false;
    scene_.materials.push_back(material);
    material_ = static_cast<MaterialId>(scene_.materials.size() - 1);
    openMesh_.reset();  // polygons after a new 'f' start a new mesh
  }

  MaterialId requireMaterial(const Token& command) const {
    if (!material_) fail(command, "no material defined yet (an 'f' line must come first)");
    return *material_;
  }

  // Spec: "s" center.x center.y center.z radius; "If the radius is negative, then only the
  // sphere's inside is visible". Prism's spheres are seen from both sides, so the sign is dropped.
  void parseSphere(const Token& command) {
    constexpr const char* kThing = "a sphere ('s')";
    SphereDesc sphere;
    sphere.material = requireMaterial(command);
    sphere.loc = loc(command);
    sphere.center = readVec3(command, kThing);
    const Number radius = readNumber(command, kThing);
    if (radius.value == 0.0f) fail(radius.token, "sphere radius must not be zero");
    sphere.radius = std::fabs(radius.value);
    scene_.spheres.push_back(sphere);
  }

  // Spec: "c" base.x base.y base.z base_radius apex.x apex.y apex.z apex_radius, open at both
  // ends; "A negative value for both radii means that only the inside of the object is visible"
  // (dropped, as for spheres) and "the base and apex cannot be coincident".
  void parseCone(const Token& command) {
    constexpr const char* kThing = "a cone ('c')";
    ConeDesc cone;
    cone.material = requireMaterial(command);
    cone.loc = loc(command);
    cone.base = readVec3(command, kThing);
    const Number baseRadius = readNumber(command, kThing);
    const Token apexToken = tokens_.peek() ? *tokens_.peek() : command;
    cone.apex = readVec3(command, kThing);
    const Number apexRadius = readNumber(command, kThing);
    // As the SPD reader does: the base radius's sign decides, and both are negated together.
    const float sign = baseRadius.value < 0.0f ? -1.0f : 1.0f;
    cone.baseRadius = sign * baseRadius.value;
    cone.apexRadius = sign * apexRadius.value;
    if (cone.apexRadius < 0.0f) {
      fail(apexRadius.token,
           "cone radii must both be negative (inside visible) or both be "
           "non-negative");
    }
    if (cone.baseRadius == 0.0f && cone.apexRadius == 0.0f) {
      fail(baseRadius.token, "cone has zero radius at both ends");
    }
    if (cone.base == cone.apex) fail(apexToken, "cone apex is at the same point as its base");
    scene_.cones.push_back(cone);
  }

  // Spec: "p" total_vertices, then the vertices, counter-clockwise seen from the visible side;
  // "pp" adds a normal after each vertex. Polygons may be concave (gears-s2.nff), so they are
  // ear-clipped. Consecutive polygons of one material share a mesh.
  void parsePolygon(const Token& command, bool patch) {
    const char* thing = patch ? "a polygon patch ('pp')" : "a polygon ('p')";
    const MaterialId material = requireMaterial(command);
    Token countToken;
    const long long count = readInteger(command, thing, &countToken);
    if (count < 3) {
      fail(countToken,
           "a polygon needs at least 3 vertices (got " + std::string(countToken.text) + ")");
    }
    polygon_.clear();
    normals_.clear();
    for (long long i = 0; i < count; ++i) {
      polygon_.push_back(readVec3(command, thing));
      if (patch) {
        const Token normalToken = tokens_.peek() ? *tokens_.peek() : command;
        const Vec3 normal = readVec3(command, thing);
        if (maxAbsComponent(normal) == 0.0f) fail(normalToken, "vertex normal has zero length");
        normals_.push_back(glm::normalize(normal));
      }
    }
    const std::vector<uint32_t> triangles = triangulatePolygon(polygon_);
    if (triangles.empty()) return;  // no area (all vertices on a line): nothing to see

    MeshDesc& mesh = meshFor(command, material, patch);
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), polygon_.begin(), polygon_.end());
    mesh.normals.insert(mesh.normals.end(), normals_.begin(), normals_.end());
    for (uint32_t index : triangles) mesh.indices.push_back(base + index);
  }

  // The mesh the next polygon joins: the open one while the material, and whether vertices carry
  // normals, stay the same (a mesh's normals are all or nothing).
  MeshDesc& meshFor(const Token& command, MaterialId material, bool patch) {
    if (!openMesh_ || openMeshIsPatch_ != patch) {
      MeshDesc mesh;
      mesh.source = "polygons";
      mesh.material = material;
      mesh.loc = loc(command);
      scene_.meshes.push_back(std::move(mesh));
      openMesh_ = scene_.meshes.size() - 1;
      openMeshIsPatch_ = patch;
    }
    return scene_.meshes[*openMesh_];
  }

  NffTokenizer tokens_;
  std::string path_;
  SceneDescription scene_;
  std::optional<MaterialId> material_;
  std::optional<size_t> openMesh_;
  bool openMeshIsPatch_ = false;
  std::vector<Vec3> polygon_;  // reused between polygons
  std::vector<Vec3> normals_;
};

}  // namespace

SceneDescription parseNff(const std::string& text, const std::string& path) {
  return NffParser(text, path).parse();
}

}  // namespace prism

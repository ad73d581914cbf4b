#include "parse/CheckedYaml.h"

#include <yaml-cpp/eventhandler.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

#include "parse/PrintableText.h"

namespace prism::yaml {
namespace {

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

}  // namespace

std::string joined(KeyTable keys, std::string_view separator) {
  std::string out;
  for (size_t i = 0; i < keys.size(); ++i) {
    if (i > 0) out += separator;
    out += keys[i];
  }
  return out;
}

// A scalar as it appears in an error message: quoted, printable, and short.
std::string shown(std::string_view text) {
  // Not "'" + string: GCC 12 warns (-Wrestrict) about that form, wrongly.
  std::string quoted = "'";
  quoted += printableExcerpt(text, 40);
  quoted += '\'';
  return quoted;
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

const Entry* Mapping::find(std::string_view key) const {
  for (const Entry& e : entries) {
    if (e.key == key) return &e;
  }
  return nullptr;
}

const Entry& Mapping::require(std::string_view key) const {
  if (const Entry* e = find(key)) return *e;
  throw SceneError(loc, what + " needs '" + std::string(key) + "'");
}

YAML::Node CheckedYaml::load(const std::string& text) const {
  try {
    checkSingleDocument(text);
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw SceneError(loc(e.mark), "invalid YAML: " + printableExcerpt(e.msg, 200));
  }
}

// A scene is one YAML document. This also guards against a yaml-cpp 0.7 bug: on some
// malformed input (a lone ',', jbeder/yaml-cpp#1040) its parser reports an empty document
// again and again without consuming anything, and YAML::LoadAll allocates until memory runs
// out. So documents are counted here, two at most, and one that makes no progress is a
// syntax error at the token that stopped it.
void CheckedYaml::checkSingleDocument(const std::string& text) const {
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

FileLoc CheckedYaml::loc(const YAML::Mark& mark) const {
  if (mark.is_null() || mark.line < 0) return FileLoc{path_};
  return FileLoc{path_, mark.line + 1, mark.column + 1};
}
FileLoc CheckedYaml::loc(const YAML::Node& node) const {
  return loc(node.Mark());
}
FileLoc CheckedYaml::loc(const Entry& e) const {
  return e.value.IsNull() ? loc(e.keyNode) : loc(e.value);
}
// A list item's own position, or the list's when the item is empty.
FileLoc CheckedYaml::itemLoc(const YAML::Node& item, const FileLoc& listLoc) const {
  return item.IsNull() ? listLoc : loc(item);
}

void CheckedYaml::fail(const FileLoc& where, const std::string& message) const {
  throw SceneError(where, message);
}

// ---- structure --------------------------------------------------------------------------

// Checks that node is a mapping with only the keys in table, each once. An empty value (as
// in "camera:" with nothing under it) is an empty mapping: everything takes its default.
Mapping CheckedYaml::mapping(const YAML::Node& node, const FileLoc& where, std::string_view what,
                             KeyTable table, std::string_view keyNoun) const {
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

Mapping CheckedYaml::mapping(const Entry& e, std::string_view what, KeyTable table) const {
  return mapping(e.value, loc(e), what, table);
}

// The items of a list section; an empty value is an empty list.
std::vector<YAML::Node> CheckedYaml::list(const Entry& e, std::string_view itemsName) const {
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

float CheckedYaml::number(const YAML::Node& node, const FileLoc& where,
                          std::string_view name) const {
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

float CheckedYaml::number(const Entry& e) const {
  return number(e.value, loc(e), e.key);
}

float CheckedYaml::positive(const Entry& e) const {
  const float v = number(e);
  if (!(v > 0.0f)) fail(loc(e), "'" + e.key + "' must be greater than 0, found " + text(e));
  return v;
}

float CheckedYaml::nonNegative(const Entry& e) const {
  const float v = number(e);
  if (v < 0.0f) fail(loc(e), "'" + e.key + "' must not be negative, found " + text(e));
  return v;
}

std::string CheckedYaml::text(const Entry& e) {
  return e.value.Scalar();
}

int64_t CheckedYaml::integer(const Entry& e, int64_t min, int64_t max) const {
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

uint64_t CheckedYaml::unsignedInteger(const Entry& e) const {
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

bool CheckedYaml::boolean(const Entry& e) const {
  const YAML::Node& node = e.value;
  if (node.IsScalar() && !isQuoted(node)) {
    const std::string& s = node.Scalar();
    if (s == "true" || s == "True" || s == "TRUE") return true;
    if (s == "false" || s == "False" || s == "FALSE") return false;
  }
  fail(loc(e), "expected true or false for '" + e.key + "', found " + describe(node));
}

std::string CheckedYaml::string(const Entry& e) const {
  const YAML::Node& node = e.value;
  if (!node.IsScalar()) {
    fail(loc(e), "expected a name for '" + e.key + "', found " + describe(node));
  }
  if (node.Scalar().empty()) fail(loc(e), "'" + e.key + "' must not be empty");
  return node.Scalar();
}

// Three numbers; with nonNegative, a negative component is reported at its own position.
Vec3 CheckedYaml::vec3(const YAML::Node& node, const FileLoc& where, std::string_view name,
                       bool nonNegative) const {
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

Vec3 CheckedYaml::vec3(const Entry& e) const {
  return vec3(e.value, loc(e), e.key);
}

Vec3 CheckedYaml::direction(const Entry& e) const {
  const Vec3 v = vec3(e);
  if (v == Vec3(0.0f)) fail(loc(e), "'" + e.key + "' must not be the zero vector");
  return glm::normalize(v);
}

// A colour is one number s (meaning [s, s, s]) or [r, g, b]; components are never negative.
Color CheckedYaml::color(const YAML::Node& node, const FileLoc& where,
                         std::string_view name) const {
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

Color CheckedYaml::color(const Entry& e) const {
  return color(e.value, loc(e), e.key);
}

}  // namespace prism::yaml

// A checked reader over yaml-cpp's node tree: typed getters that report every mistake at its own
// file:line:col with what was expected and what was found, mappings checked against a table of
// known keys (no unknown and no duplicate keys), and a loader that insists on one document.
// It knows nothing of scenes; YamlSceneReader.h writes the scene schema with it. It never uses
// yaml-cpp's as<T>() conversions: their errors do not say which key was wrong.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "math/Vec.h"
#include "scene/SettingLimits.h"
#include "scene/SettingNames.h"
#include "util/FileLoc.h"

namespace prism::yaml {

using KeyTable = std::span<const std::string_view>;

// "a, b, c".
std::string joined(KeyTable keys, std::string_view separator = ", ");
// A scalar as it appears in an error message: quoted, printable, and short.
std::string shown(std::string_view text);
// What a node holds, for "found ..." in messages ("a list of 2 items", "'abc'", "nothing").
std::string describe(const YAML::Node& node);

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

  const Entry* find(std::string_view key) const;
  const Entry& require(std::string_view key) const;  // throws "sphere needs 'radius'"
};

// Every getter throws SceneError at the value's position.
class CheckedYaml {
 public:
  explicit CheckedYaml(std::string path) : path_(std::move(path)) {}

  const std::string& path() const { return path_; }

  // Parses text as exactly one YAML document; syntax errors become SceneErrors.
  YAML::Node load(const std::string& text) const;

  // ---- positions and messages
  FileLoc loc(const YAML::Mark& mark) const;
  FileLoc loc(const YAML::Node& node) const;
  FileLoc loc(const Entry& e) const;
  // A list item's own position, or the list's when the item is empty.
  FileLoc itemLoc(const YAML::Node& item, const FileLoc& listLoc) const;
  [[noreturn]] void fail(const FileLoc& where, const std::string& message) const;

  // ---- structure
  // node as a mapping with only the keys in table, each once. An empty value (as in "camera:"
  // with nothing under it) is an empty mapping: everything takes its default.
  Mapping mapping(const YAML::Node& node, const FileLoc& where, std::string_view what,
                  KeyTable table, std::string_view keyNoun = "key") const;
  Mapping mapping(const Entry& e, std::string_view what, KeyTable table) const;
  // The items of a list section; an empty value is an empty list.
  std::vector<YAML::Node> list(const Entry& e, std::string_view itemsName) const;

  // ---- values
  float number(const YAML::Node& node, const FileLoc& where, std::string_view name) const;
  float number(const Entry& e) const;
  float positive(const Entry& e) const;
  float nonNegative(const Entry& e) const;
  static std::string text(const Entry& e);  // the value as written
  int64_t integer(const Entry& e, int64_t min, int64_t max) const;
  int64_t integer(const Entry& e, const SettingLimit& limit) const {
    return integer(e, limit.min, limit.max);
  }
  uint64_t unsignedInteger(const Entry& e) const;
  bool boolean(const Entry& e) const;
  std::string string(const Entry& e) const;  // a non-empty name

  // One of the names of a setting's table (SettingNames.h).
  template <typename T>
  T choice(const Entry& e, const NameTable<T>& names) const {
    if (!e.value.IsScalar()) {
      fail(loc(e), "expected " + names.list() + " for '" + e.key + "', found " + describe(e.value));
    }
    if (const std::optional<T> value = names.find(e.value.Scalar())) return *value;
    fail(loc(e),
         "unknown " + e.key + " " + shown(e.value.Scalar()) + " (expected " + names.list() + ")");
  }

  // Three numbers; with nonNegative, a negative component is reported at its own position.
  Vec3 vec3(const YAML::Node& node, const FileLoc& where, std::string_view name,
            bool nonNegative = false) const;
  Vec3 vec3(const Entry& e) const;
  Vec3 direction(const Entry& e) const;  // non-zero, normalised
  // A colour is one number s (meaning [s, s, s]) or [r, g, b]; components are never negative.
  Color color(const YAML::Node& node, const FileLoc& where, std::string_view name) const;
  Color color(const Entry& e) const;

 private:
  void checkSingleDocument(const std::string& text) const;

  std::string path_;
};

}  // namespace prism::yaml

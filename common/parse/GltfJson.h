// A checked walk over a glTF's JSON (simdjson's DOM): every value keeps its JSON path
// ("accessors[3].count"), so a value of the wrong type or out of range is reported as
// "file: accessors[3].count: what is wrong". The walker reads; what the values mean is the
// loader's (GltfLoader.cpp and its parts).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <simdjson.h>

#include "util/FileLoc.h"

namespace prism {

class GltfJson {
 public:
  GltfJson(simdjson::dom::element value, std::string path, const std::string* file)
      : value_(value), path_(std::move(path)), file_(file) {}

  const std::string& path() const { return path_; }
  const std::string& file() const { return *file_; }
  bool isObject() const { return value_.is_object(); }
  bool isArray() const { return value_.is_array(); }
  bool isString() const { return value_.is_string(); }

  // Throws SceneError "file: path: message".
  [[noreturn]] void fail(const std::string& message) const;

  // The member of an object (this must be one: checked); nothing when it is absent.
  std::optional<GltfJson> member(std::string_view key) const;
  GltfJson required(std::string_view key) const;
  // The keys of an object, in the file's order.
  std::vector<std::string_view> keys() const;
  // The items of an array.
  std::vector<GltfJson> items() const;

  uint64_t index() const;  // a non-negative integer
  double number() const;   // any finite number
  std::string_view string() const;
  bool boolean() const;
  void expectObject() const;

  // Conveniences for optional members with defaults.
  std::optional<uint64_t> optionalIndex(std::string_view key) const;
  uint64_t indexOr(std::string_view key, uint64_t fallback) const;
  double numberOr(std::string_view key, double fallback) const;
  std::string_view stringOr(std::string_view key, std::string_view fallback) const;
  bool booleanOr(std::string_view key, bool fallback) const;
  // An array of exactly n numbers (an absent member: fallback, which has n numbers).
  std::vector<double> numbersOr(std::string_view key, size_t n,
                                const std::vector<double>& fallback) const;
  // Members that are arrays of objects (meshes, nodes, ...); an absent one is empty.
  std::vector<GltfJson> objectsOf(std::string_view key) const;

 private:
  std::string describe() const;  // "a string", "an object", ...
  simdjson::dom::element value_;
  std::string path_;
  const std::string* file_;
};

// A glTF's parsed JSON text: the parser owns the document the root points into.
class GltfJsonDocument {
 public:
  // Parses text; throws SceneError at file naming what simdjson found wrong.
  GltfJsonDocument(std::string_view text, const std::string& file);
  GltfJson root() const { return {root_, "", &file_}; }

 private:
  std::string file_;
  simdjson::dom::parser parser_;
  simdjson::dom::element root_;
};

// The bytes simdjson's DOM takes for a JSON text of this size, at most: a padded copy, the
// string buffer (no larger than the text) and the tape (8 bytes per value; a value takes at
// least 2 bytes of text), plus the structural index (4 bytes per structural character).
inline uint64_t gltfJsonParseBytes(uint64_t textBytes) {
  return textBytes * 9 + 4096;
}

}  // namespace prism

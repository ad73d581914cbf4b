#include "parse/GltfJson.h"

#include <cmath>

namespace prism {

namespace {

std::string childPath(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

}  // namespace

void GltfJson::fail(const std::string& message) const {
  throw SceneError(FileLoc{*file_, 0, 0}, path_.empty() ? message : path_ + ": " + message);
}

std::string GltfJson::describe() const {
  switch (value_.type()) {
    case simdjson::dom::element_type::ARRAY:
      return "an array";
    case simdjson::dom::element_type::OBJECT:
      return "an object";
    case simdjson::dom::element_type::INT64:
    case simdjson::dom::element_type::UINT64:
    case simdjson::dom::element_type::DOUBLE:
      return "a number";
    case simdjson::dom::element_type::STRING:
      return "a string";
    case simdjson::dom::element_type::BOOL:
      return "a boolean";
    case simdjson::dom::element_type::NULL_VALUE:
      return "null";
  }
  return "a value";
}

void GltfJson::expectObject() const {
  if (!value_.is_object()) fail("expected an object, found " + describe());
}

std::optional<GltfJson> GltfJson::member(std::string_view key) const {
  expectObject();
  simdjson::dom::element child;
  if (value_.get_object().at_key(key).get(child) != simdjson::SUCCESS) return std::nullopt;
  return GltfJson(child, childPath(path_, key), file_);
}

GltfJson GltfJson::required(std::string_view key) const {
  std::optional<GltfJson> child = member(key);
  if (!child) fail("'" + std::string(key) + "' is missing");
  return *child;
}

std::vector<std::string_view> GltfJson::keys() const {
  expectObject();
  std::vector<std::string_view> out;
  const simdjson::dom::object object = value_.get_object().value_unsafe();
  for (const simdjson::dom::key_value_pair field : object) {
    out.push_back(field.key);
  }
  return out;
}

std::vector<GltfJson> GltfJson::items() const {
  if (!value_.is_array()) fail("expected an array, found " + describe());
  std::vector<GltfJson> out;
  const simdjson::dom::array array = value_.get_array().value_unsafe();
  out.reserve(array.size());
  for (const simdjson::dom::element item : array) {
    out.emplace_back(item, path_ + "[" + std::to_string(out.size()) + "]", file_);
  }
  return out;
}

uint64_t GltfJson::index() const {
  uint64_t n = 0;
  if (value_.get_uint64().get(n) == simdjson::SUCCESS) return n;
  double d = 0.0;
  // 3.0 is an integer too (some exporters write counts as floats).
  if (value_.get_double().get(d) == simdjson::SUCCESS && d >= 0.0 && d < 1.8e19 &&
      d == std::floor(d)) {
    return static_cast<uint64_t>(d);
  }
  fail("expected an integer of 0 or more, found " +
       (value_.is_number() ? std::string("a negative or fractional number") : describe()));
}

double GltfJson::number() const {
  double d = 0.0;
  if (!value_.is_number() || value_.get_double().get(d) != simdjson::SUCCESS) {
    fail("expected a number, found " + describe());
  }
  if (!std::isfinite(d)) fail("the number is not finite");
  return d;
}

std::string_view GltfJson::string() const {
  std::string_view s;
  if (value_.get_string().get(s) != simdjson::SUCCESS)
    fail("expected a string, found " + describe());
  return s;
}

bool GltfJson::boolean() const {
  bool b = false;
  if (value_.get_bool().get(b) != simdjson::SUCCESS)
    fail("expected true or false, found " + describe());
  return b;
}

std::optional<uint64_t> GltfJson::optionalIndex(std::string_view key) const {
  const std::optional<GltfJson> child = member(key);
  if (!child) return std::nullopt;
  return child->index();
}

uint64_t GltfJson::indexOr(std::string_view key, uint64_t fallback) const {
  return optionalIndex(key).value_or(fallback);
}

double GltfJson::numberOr(std::string_view key, double fallback) const {
  const std::optional<GltfJson> child = member(key);
  return child ? child->number() : fallback;
}

std::string_view GltfJson::stringOr(std::string_view key, std::string_view fallback) const {
  const std::optional<GltfJson> child = member(key);
  return child ? child->string() : fallback;
}

bool GltfJson::booleanOr(std::string_view key, bool fallback) const {
  const std::optional<GltfJson> child = member(key);
  return child ? child->boolean() : fallback;
}

std::vector<double> GltfJson::numbersOr(std::string_view key, size_t n,
                                        const std::vector<double>& fallback) const {
  const std::optional<GltfJson> child = member(key);
  if (!child) return fallback;
  const std::vector<GltfJson> values = child->items();
  if (values.size() != n) {
    child->fail("expected " + std::to_string(n) + " numbers, found " +
                std::to_string(values.size()));
  }
  std::vector<double> out;
  out.reserve(n);
  for (const GltfJson& v : values) out.push_back(v.number());
  return out;
}

std::vector<GltfJson> GltfJson::objectsOf(std::string_view key) const {
  const std::optional<GltfJson> child = member(key);
  if (!child) return {};
  std::vector<GltfJson> out = child->items();
  for (const GltfJson& item : out) item.expectObject();
  return out;
}

GltfJsonDocument::GltfJsonDocument(std::string_view text, const std::string& file) : file_(file) {
  const simdjson::error_code error = parser_.parse(text.data(), text.size()).get(root_);
  if (error != simdjson::SUCCESS) {
    throw SceneError(FileLoc{file, 0, 0},
                     std::string("not valid JSON: ") + simdjson::error_message(error));
  }
  if (!root_.is_object()) {
    throw SceneError(FileLoc{file, 0, 0}, "not a glTF file: the JSON is not an object");
  }
}

}  // namespace prism

// Small glTF models written by the tests (tests/common/parse/Gltf*_test.cpp, the fuzz seeds): a
// binary buffer built value by value and the JSON around it, as a .gltf with a base64 data URI,
// as a .glb, or as a .gltf beside a .bin file. Known answers stay readable in the test itself.
#pragma once

#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "parse/GltfLoader.h"

namespace prism::gltftest {

inline std::string base64(std::string_view bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = uint8_t(bytes[i]) << 16 | uint8_t(bytes[i + 1]) << 8 | uint8_t(bytes[i + 2]);
    for (int k = 3; k >= 0; --k) out += kAlphabet[(v >> (6 * k)) & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const uint32_t v = uint8_t(bytes[i]) << 16 | (two ? uint8_t(bytes[i + 1]) << 8 : 0);
    out += kAlphabet[v >> 18];
    out += kAlphabet[(v >> 12) & 63];
    out += two ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

class GltfAssets {
 public:
  // Appends raw bytes (4-byte aligned) and a buffer view of them; returns the view's index.
  int view(std::string_view bytes, int stride = 0) {
    while (bin.size() % 4) bin += '\0';
    std::string v = "{\"buffer\":0,\"byteOffset\":" + std::to_string(bin.size()) +
                    ",\"byteLength\":" + std::to_string(bytes.size());
    if (stride) v += ",\"byteStride\":" + std::to_string(stride);
    views.push_back(v + "}");
    bin.append(bytes);
    return static_cast<int>(views.size() - 1);
  }
  template <class T>
  int view(const std::vector<T>& values, int stride = 0) {
    return view(
        std::string_view(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)),
        stride);
  }
  int accessor(int view, int componentType, size_t count, const char* type,
               const std::string& extra = "") {
    std::string a = "{\"componentType\":" + std::to_string(componentType) +
                    ",\"count\":" + std::to_string(count) + ",\"type\":\"" + type + "\"";
    if (view >= 0) a += ",\"bufferView\":" + std::to_string(view);
    accessors.push_back(a + extra + "}");
    return static_cast<int>(accessors.size() - 1);
  }
  // Floats tightly packed, `perElement` to an element of `type`.
  int floats(const std::vector<float>& values, const char* type, int perElement) {
    return accessor(view(values), 5126, values.size() / perElement, type);
  }
  int indices(const std::vector<uint16_t>& values) {
    return accessor(view(values), 5123, values.size(), "SCALAR");
  }
  int indices32(const std::vector<uint32_t>& values) {
    return accessor(view(values), 5125, values.size(), "SCALAR");
  }

  // The whole JSON: `body` holds the other top-level members, e.g. "\"meshes\":[...]".
  std::string json(const std::string& body, const std::optional<std::string>& bufferUri) const {
    std::string j = "{\"asset\":{\"version\":\"2.0\"}";
    if (!bin.empty()) {
      j += ",\"buffers\":[{";
      if (bufferUri) j += "\"uri\":\"" + *bufferUri + "\",";
      j += "\"byteLength\":" + std::to_string(bin.size()) + "}]";
      j += ",\"bufferViews\":[" + joined(views) + "]";
      j += ",\"accessors\":[" + joined(accessors) + "]";
    }
    if (!body.empty()) j += "," + body;
    return j + "}";
  }
  std::string gltf(const std::string& body) const {
    return json(body, "data:application/octet-stream;base64," + base64(bin));
  }
  std::string glb(const std::string& body) const {
    std::string j = json(body, std::nullopt);
    while (j.size() % 4) j += ' ';
    std::string b = bin;
    while (b.size() % 4) b += '\0';
    std::string out = "glTF";
    put(out, 2);
    put(out, static_cast<uint32_t>(12 + 8 + j.size() + (b.empty() ? 0 : 8 + b.size())));
    put(out, static_cast<uint32_t>(j.size()));
    out += "JSON";
    out += j;
    if (!b.empty()) {
      put(out, static_cast<uint32_t>(b.size()));
      out.append("BIN\0", 4);
      out += b;
    }
    return out;
  }

  std::string bin;
  std::vector<std::string> views, accessors;

 private:
  static std::string joined(const std::vector<std::string>& parts) {
    std::string out;
    for (const std::string& p : parts) out += (out.empty() ? "" : ",") + p;
    return out;
  }
  static void put(std::string& out, uint32_t v) {
    out.append(reinterpret_cast<const char*>(&v), 4);
  }
};

// A file reader over files held in memory.
inline GltfFileReader filesIn(const std::map<std::string, std::string>& files) {
  return [&files](const std::string& path) -> std::optional<std::string_view> {
    const auto found = files.find(path);
    if (found == files.end()) return std::nullopt;
    return std::string_view(found->second);
  };
}

inline ModelDesc parse(const std::string& bytes, const std::string& name = "model.gltf",
                       const std::map<std::string, std::string>& files = {},
                       const MemoryLimit& limit = {}) {
  return parseGltfModel(bytes, name, filesIn(files), FileLoc{}, limit);
}

// One triangle (0,0,0), (1,0,0), (0,1,0) placed by node 0 with the node's JSON members.
inline std::string oneTriangle(GltfAssets& a, const std::string& nodeMembers = "",
                               const std::string& more = "") {
  const int p = a.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  return "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0" +
         (nodeMembers.empty() ? "" : "," + nodeMembers) +
         "}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(p) +
         "}}]}]" + more;
}

}  // namespace prism::gltftest

#include "parse/PlyLoader.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "image/SrgbImage.h"
#include "image/ToneMap.h"
#include "parse/MeshFileBytes.h"
#include "parse/PlyBody.h"
#include "parse/PrintableText.h"
#include "parse/UsableNormal.h"
#include "scene/MeshBudget.h"
#include "util/HugePages.h"
#include "util/Parallel.h"

namespace prism {

namespace {

// The vertex properties Prism reads, by role.
enum Role { kX, kY, kZ, kNx, kNy, kNz, kU, kV, kRed, kGreen, kBlue, kRoles };

// The names each role may go by, the first the usual one.
const std::vector<std::vector<const char*>>& roleNames() {
  static const std::vector<std::vector<const char*>> names = {{"x"},
                                                              {"y"},
                                                              {"z"},
                                                              {"nx"},
                                                              {"ny"},
                                                              {"nz"},
                                                              {"u", "s", "texture_u", "texture_s"},
                                                              {"v", "t", "texture_v", "texture_t"},
                                                              {"red"},
                                                              {"green"},
                                                              {"blue"}};
  return names;
}

// How a colour property's values become linear colour: floats are linear already; integers
// are sRGB-encoded fractions of their type's largest value (uchar: bytes, through a table).
class ColourChannel {
 public:
  explicit ColourChannel(PlyType type) : type_(type) {
    switch (type) {
      case PlyType::Int8:
        largest_ = 127.0;
        break;
      case PlyType::UInt8:
        largest_ = 255.0;
        break;
      case PlyType::Int16:
        largest_ = 32767.0;
        break;
      case PlyType::UInt16:
        largest_ = 65535.0;
        break;
      case PlyType::Int32:
        largest_ = 2147483647.0;
        break;
      case PlyType::UInt32:
        largest_ = 4294967295.0;
        break;
      case PlyType::Float32:
      case PlyType::Float64:
        break;
    }
  }
  bool isLinear() const { return largest_ == 0.0; }
  float operator()(float value) const {
    if (isLinear()) return value;
    if (type_ == PlyType::UInt8) return linearOfSrgbByte()[static_cast<uint8_t>(value)];
    return srgbToLinear(static_cast<float>(std::clamp(value / largest_, 0.0, 1.0)));
  }

 private:
  PlyType type_;
  double largest_ = 0.0;
};

// What the mesh is made of: the vertex and face elements and where their properties are.
struct PlyLayout {
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;
  int role[kRoles] = {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};  // property index per role
  bool normals = false;
  bool uvs = false;
  bool colors = false;
  std::vector<ColourChannel> colour;  // red, green, blue, where the vertex has colours
  int indices = -1;                   // property index of the face's vertex list
};

PlyLayout layoutOf(const PlyHeader& header, const std::string& path) {
  PlyLayout layout;
  layout.vertex = header.find("vertex");
  layout.face = header.find("face");
  if (!layout.vertex) throw SceneError(FileLoc{path, 0, 0}, "the file has no 'vertex' element");
  if (!layout.face) {
    throw SceneError(FileLoc{path, 0, 0}, "the file has no 'face' element (no triangles)");
  }
  const FileLoc vertexLoc{path, layout.vertex->line, 1};
  for (int r = 0; r < kRoles; ++r) {
    for (const char* name : roleNames()[static_cast<size_t>(r)]) {
      const int k = layout.vertex->find(name);
      if (k < 0) continue;
      if (layout.vertex->properties[static_cast<size_t>(k)].isList) {
        throw SceneError(vertexLoc,
                         std::string("vertex property '") + name + "' is a list, not a number");
      }
      layout.role[r] = k;
      break;
    }
  }
  for (int r = 0; r < 3; ++r) {
    if (layout.role[r] < 0) {
      throw SceneError(vertexLoc, std::string("the vertex element has no '") +
                                      roleNames()[static_cast<size_t>(r)][0] + "' property");
    }
  }
  layout.normals = layout.role[kNx] >= 0 && layout.role[kNy] >= 0 && layout.role[kNz] >= 0;
  layout.uvs = layout.role[kU] >= 0 && layout.role[kV] >= 0;
  layout.colors = layout.role[kRed] >= 0 && layout.role[kGreen] >= 0 && layout.role[kBlue] >= 0;
  if (layout.colors) {
    for (int r = kRed; r <= kBlue; ++r) {
      layout.colour.emplace_back(
          layout.vertex->properties[static_cast<size_t>(layout.role[r])].type);
    }
  }
  layout.indices = layout.face->find("vertex_indices");
  if (layout.indices < 0) layout.indices = layout.face->find("vertex_index");
  const FileLoc faceLoc{path, layout.face->line, 1};
  if (layout.indices < 0) {
    throw SceneError(faceLoc, "the face element has no 'vertex_indices' list");
  }
  const PlyProperty& list = layout.face->properties[static_cast<size_t>(layout.indices)];
  if (!list.isList || !isPlyIntegerType(list.type)) {
    throw SceneError(faceLoc, "'" + list.name + "' must be a list of integers");
  }
  if (layout.vertex->count > 0xffffffffu) {
    throw SceneError(vertexLoc, "more vertices than 32-bit indices can number");
  }
  return layout;
}

template <class Body>
class PlyReader {
 public:
  PlyReader(Body& body, const PlyLayout& layout, MeshDesc& mesh)
      : body_(body), layout_(layout), mesh_(mesh) {}

  void read(const PlyHeader& header) {
    for (const PlyElement& element : header.elements) {
      if constexpr (Body::kBinary) {
        if (&element == layout_.vertex && verticesAtOnce(element)) continue;
        if (&element == layout_.face && trianglesAtOnce(element)) continue;
      }
      for (uint64_t i = 0; i < element.count; ++i) {
        try {
          if (&element == layout_.vertex) {
            readVertex(element, i);
          } else if (&element == layout_.face) {
            readFace(element);
          } else {
            for (const PlyProperty& property : element.properties) skip(property);
          }
        } catch (const PlyBodyFailure& failure) {
          throw SceneError(body_.loc(), printableExcerpt(element.name) + " " + std::to_string(i) +
                                            body_.position() + ": " + failure.message);
        }
      }
    }
  }

 private:
  // Elements handed to each thread at a time by the readers below.
  static constexpr uint64_t kBlock = uint64_t{1} << 16;

  // Binary vertices of fixed size (no list among their properties), on all cores. False, with
  // nothing consumed, where they are not of fixed size, run past the file's end or hold a
  // non-finite number: read one by one, which names the first such vertex.
  bool verticesAtOnce(const PlyElement& element) {
    std::vector<size_t> offsets;
    size_t stride = 0;
    for (const PlyProperty& property : element.properties) {
      if (property.isList) return false;
      offsets.push_back(stride);
      stride += static_cast<size_t>(plyTypeBytes(property.type));
    }
    const uint64_t count = element.count;
    if (stride == 0 || body_.remaining() / stride < count) return false;
    struct Value {
      int role;
      size_t offset;
      PlyType type;
    };
    std::vector<Value> values;
    bool allFloats = true;
    for (int r = 0; r < kRoles; ++r) {
      if (layout_.role[r] < 0) continue;
      const PlyType type = element.properties[static_cast<size_t>(layout_.role[r])].type;
      values.push_back({r, offsets[static_cast<size_t>(layout_.role[r])], type});
      allFloats = allFloats && type == PlyType::Float32;
    }
    const char* const base = body_.cursor();
    std::atomic<bool> nonFinite{false};
    // Positions and normals alone (most big meshes) are stored as they were before texture
    // coordinates and colours were read.
    const bool attributes = layout_.uvs || layout_.colors;
    const bool normals = layout_.normals;
    parallelFor((count + kBlock - 1) / kBlock, 0, [&](uint64_t block) {
      const uint64_t end = std::min(count, (block + 1) * kBlock);
      for (uint64_t i = block * kBlock; i < end; ++i) {
        const char* record = base + i * stride;
        float v[kRoles] = {};
        bool finite = true;
        for (const Value& value : values) {
          // The usual case, all floats, without a switch per number.
          v[value.role] =
              allFloats ? Body::template decode<float>(record + value.offset)
                        : static_cast<float>(Body::decodeNumber(value.type, record + value.offset));
          finite = finite && std::isfinite(v[value.role]);
        }
        if (!finite) nonFinite = true;
        if (attributes) {
          store(i, v);
        } else {
          mesh_.positions[i] = Vec3(v[kX], v[kY], v[kZ]);
          if (normals) mesh_.normals[i] = Vec3(v[kNx], v[kNy], v[kNz]);
        }
      }
    });
    if (nonFinite || (layout_.colors && !coloursValid(count))) return false;
    body_.advance(count * stride);
    return true;
  }

  // Binary faces whose only property is the index list, with a one-byte length and four-byte
  // indices, as triangles, on all cores. False, with nothing kept, where a face is not a
  // triangle, names a vertex the file lacks or runs past the file's end: read one by one, which
  // splits polygons and names the first bad face.
  bool trianglesAtOnce(const PlyElement& element) {
    if (element.properties.size() != 1 || layout_.indices != 0) return false;
    const PlyProperty& list = element.properties[0];
    if (plyTypeBytes(list.countType) != 1 || plyTypeBytes(list.type) != 4) return false;
    constexpr size_t kRecord = 1 + 3 * 4;
    const uint64_t count = element.count;
    if (body_.remaining() / kRecord < count) return false;
    const bool signedIndices = list.type == PlyType::Int32;
    const uint64_t vertices = layout_.vertex->count;
    const char* const base = body_.cursor();
    mesh_.indices.resize(3 * count);
    std::atomic<bool> other{false};
    parallelFor((count + kBlock - 1) / kBlock, 0, [&](uint64_t block) {
      const uint64_t end = std::min(count, (block + 1) * kBlock);
      for (uint64_t f = block * kBlock; f < end; ++f) {
        const char* record = base + f * kRecord;
        if (static_cast<uint8_t>(record[0]) != 3) {
          other = true;
          return;
        }
        for (int c = 0; c < 3; ++c) {
          const char* at = record + 1 + 4 * c;
          const int64_t index = signedIndices ? Body::template decode<int32_t>(at)
                                              : Body::template decode<uint32_t>(at);
          if (index < 0 || static_cast<uint64_t>(index) >= vertices) {
            other = true;
            return;
          }
          mesh_.indices[3 * f + static_cast<uint64_t>(c)] = static_cast<uint32_t>(index);
        }
      }
    });
    if (other) {
      mesh_.indices.clear();
      return false;
    }
    body_.advance(count * kRecord);
    return true;
  }

  void skip(const PlyProperty& property) {
    if (!property.isList) return body_.skip(property.type);
    const int64_t n = body_.integer(property.countType);
    if (n < 0) throw PlyBodyFailure{"a list of negative length"};
    for (int64_t k = 0; k < n; ++k) body_.skip(property.type);
  }

  // A vertex's values by role into the mesh.
  void store(uint64_t i, const float (&v)[kRoles]) {
    mesh_.positions[i] = Vec3(v[kX], v[kY], v[kZ]);
    if (layout_.normals) mesh_.normals[i] = Vec3(v[kNx], v[kNy], v[kNz]);
    if (layout_.uvs) mesh_.uvs[i] = Vec2(v[kU], v[kV]);
    if (layout_.colors) {
      mesh_.colors[i] = Color(layout_.colour[0](v[kRed]), layout_.colour[1](v[kGreen]),
                              layout_.colour[2](v[kBlue]));
    }
  }

  // Whether no colour is negative (float colours; integers are clamped): read one by one
  // otherwise, which names the first.
  bool coloursValid(uint64_t count) const {
    for (uint64_t i = 0; i < count; ++i) {
      const Color& c = mesh_.colors[i];
      if (c.r < 0.0f || c.g < 0.0f || c.b < 0.0f) return false;
    }
    return true;
  }

  void readVertex(const PlyElement& element, uint64_t i) {
    float values[kRoles] = {};
    for (size_t k = 0; k < element.properties.size(); ++k) {
      const PlyProperty& property = element.properties[k];
      const int role = roleOf(static_cast<int>(k));
      if (role < 0) {
        skip(property);
        continue;
      }
      const auto value = static_cast<float>(body_.number(property.type));
      if (!std::isfinite(value)) {
        throw PlyBodyFailure{"non-finite '" + property.name + "'"};
      }
      if (role >= kRed && value < 0.0f && !isPlyIntegerType(property.type)) {
        throw PlyBodyFailure{"negative colour '" + property.name + "'"};
      }
      values[role] = value;
    }
    store(i, values);
  }

  int roleOf(int property) const {
    for (int r = 0; r < kRoles; ++r) {
      if (layout_.role[r] == property) return r;
    }
    return -1;
  }

  void readFace(const PlyElement& element) {
    for (size_t k = 0; k < element.properties.size(); ++k) {
      const PlyProperty& property = element.properties[k];
      if (static_cast<int>(k) != layout_.indices) {
        skip(property);
        continue;
      }
      const int64_t n = body_.integer(property.countType);
      if (n < 3) {
        throw PlyBodyFailure{"a face needs at least 3 vertices but this one has " +
                             std::to_string(n)};
      }
      // A fan around the first corner: (0, 1, 2), (0, 2, 3), ...
      const uint32_t first = index(property.type);
      uint32_t previous = index(property.type);
      for (int64_t c = 2; c < n; ++c) {
        const uint32_t next = index(property.type);
        mesh_.indices.insert(mesh_.indices.end(), {first, previous, next});
        previous = next;
      }
    }
  }

  uint32_t index(PlyType type) {
    const int64_t i = body_.integer(type);
    if (i < 0 || static_cast<uint64_t>(i) >= layout_.vertex->count) {
      throw PlyBodyFailure{"face refers to vertex " + std::to_string(i) + " but the file has " +
                           std::to_string(layout_.vertex->count) + " (counted from 0)"};
    }
    return static_cast<uint32_t>(i);
  }

  Body& body_;
  const PlyLayout& layout_;
  MeshDesc& mesh_;
};

}  // namespace

MeshDesc parsePlyMesh(std::string_view bytes, const std::string& path,
                      const FileLoc& referencedFrom, const MemoryLimit& limit) {
  const PlyHeader header = parsePlyHeader(bytes, path);
  const PlyLayout layout = layoutOf(header, path);
  const uint64_t vertices = layout.vertex->count;
  // Every face is at least one triangle; the header checked that the body can hold them all.
  const uint64_t triangles = layout.face->count;
  const uint64_t needed = saturatingAdd(
      plyReadBytes(bytes.size(), vertices, layout.normals, layout.uvs, layout.colors, triangles),
      meshBuildBytes(triangles, vertices));
  if (needed > limit.bytes) {
    throw SceneError(
        referencedFrom.file.empty() ? FileLoc{path, 0, 0} : referencedFrom,
        memoryRefusal("mesh file '" + path + "' (at least " + std::to_string(triangles) +
                          " triangles, " + std::to_string(vertices) + " vertices) read and built",
                      needed, limit, "simplify the mesh or raise --memory-limit"));
  }

  MeshDesc mesh;
  mesh.source = path;
  mesh.loc = referencedFrom;
  reserveOnHugePages(mesh.positions, vertices);
  mesh.positions.resize(vertices);
  if (layout.normals) {
    reserveOnHugePages(mesh.normals, vertices);
    mesh.normals.resize(vertices);
  }
  if (layout.uvs) {
    reserveOnHugePages(mesh.uvs, vertices);
    mesh.uvs.resize(vertices);
  }
  if (layout.colors) {
    reserveOnHugePages(mesh.colors, vertices);
    mesh.colors.resize(vertices);
  }
  reserveOnHugePages(mesh.indices, 3 * triangles);
  switch (header.format) {
    case PlyFormat::Ascii: {
      AsciiPlyBody body(bytes, header.bodyOffset, header.bodyLine, path);
      PlyReader<AsciiPlyBody>(body, layout, mesh).read(header);
      break;
    }
    case PlyFormat::BinaryLittleEndian: {
      BinaryPlyBody<false> body(bytes, header.bodyOffset, path);
      PlyReader<BinaryPlyBody<false>>(body, layout, mesh).read(header);
      break;
    }
    case PlyFormat::BinaryBigEndian: {
      BinaryPlyBody<true> body(bytes, header.bodyOffset, path);
      PlyReader<BinaryPlyBody<true>>(body, layout, mesh).read(header);
      break;
    }
  }
  if (mesh.indices.empty()) throw SceneError(FileLoc{path, 0, 0}, "mesh file has no triangles");
  // Polygons made more triangles than faces: the limit is checked again with the true count.
  const uint64_t made = mesh.triangleCount();
  const uint64_t neededAfter = saturatingAdd(
      plyReadBytes(bytes.size(), vertices, layout.normals, layout.uvs, layout.colors, made),
      meshBuildBytes(made, vertices));
  if (neededAfter > limit.bytes) {
    throw SceneError(
        referencedFrom.file.empty() ? FileLoc{path, 0, 0} : referencedFrom,
        memoryRefusal("mesh file '" + path + "' (" + std::to_string(made) + " triangles, " +
                          std::to_string(vertices) + " vertices) read and built",
                      neededAfter, limit, "simplify the mesh or raise --memory-limit"));
  }
  // A normal that cannot be normalised (zero, say) leaves the mesh flat, as it would an OBJ mesh.
  for (Vec3& n : mesh.normals) {
    if (!isUsableNormal(n)) {
      std::vector<Vec3>().swap(mesh.normals);
      break;
    }
    n = glm::normalize(n);
  }
  return mesh;
}

MeshDesc loadPlyMesh(const std::string& path, const FileLoc& referencedFrom,
                     const MemoryLimit& limit) {
  MeshFileBytes file(path, referencedFrom, limit);
  return parsePlyMesh(file.bytes(), path, referencedFrom, limit);
}

}  // namespace prism

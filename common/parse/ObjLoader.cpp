// OBJ models, read on several threads. The text is cut at line ends (LineChunks.h); each piece is
// counted, then parsed straight into arrays shared by all pieces (ObjChunk.h), in file order,
// so the result is the same however the text is cut. What is read: 'v' positions, 'vn' normals,
// 'vt' texture coordinates and 'f' faces (v, v/vt, v//vn, v/vt/vn corners; negative indices
// count back from the statement), 'mtllib' libraries (ObjMaterials.h) and 'usemtl'. Everything
// else ('g', 'o', 's', 'l', 'p', ...) is skipped. Faces of four or more corners are ear-clipped
// by PolygonTriangulator, as NFF polygons are.
#include "parse/ObjLoader.h"

#include <algorithm>
#include <unordered_map>

#include "parse/LineChunks.h"
#include "parse/MeshFileBytes.h"
#include "parse/ObjChunk.h"
#include "parse/ObjMaterials.h"
#include "parse/PolygonTriangulator.h"
#include "parse/PrintableText.h"
#include "parse/UsableNormal.h"
#include "scene/MeshBudget.h"
#include "util/HugePages.h"
#include "util/Parallel.h"

namespace prism {

namespace {

// Pieces of about this size: enough of them that threads share the work evenly, large enough
// that a piece's fixed costs vanish; inputs smaller than one piece are read on the calling thread.
constexpr size_t kPieceBytes = size_t{4} << 20;

// v.resize(n), with 2 MiB pages under it before the zeros are written: a page fault per 4 KiB
// was an eighth of the whole read on a virtual machine.
template <class T>
void sizeOnHugePages(std::vector<T>& v, size_t n) {
  reserveOnHugePages(v, n);
  v.resize(n);
}

// The face corners as the file wrote them, resolved to 0-based indices, and everything the
// pieces read.
struct ObjArrays {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<Vec2> uvs;
  std::vector<uint32_t> cornerVertex;
  std::vector<uint32_t> cornerNormal;  // empty when the file has no normals
  std::vector<uint32_t> cornerUv;      // empty when the file has no texture coordinates
  std::vector<uint8_t> faceCorners;
  std::vector<uint32_t> faceMaterial;  // empty when the file has no 'usemtl'
  bool cornerWithoutNormal = false;
  bool cornerWithUv = false;
  uint64_t firstLineWithoutUv = 0;
  std::vector<ObjUnknownMaterial> unknownMaterials;
};

// One output vertex per distinct (position, normal, texture coordinate), numbered in the order
// the corners first use them, so normals and texture coordinates can be indexed like positions.
// Most positions come with one normal and one texture coordinate (or none): the first of each
// position is kept in flat arrays and only the others in a map.
class VertexNumbering {
 public:
  VertexNumbering(size_t positions, bool smooth, bool textured)
      : smooth_(smooth), textured_(textured), firstId_(positions, kUnseen) {
    if (smooth_) firstNormal_.resize(positions);
    if (textured_) firstUv_.resize(positions);
    reserveOnHugePages(sourcePosition_, positions);
    if (smooth_) reserveOnHugePages(sourceNormal_, positions);
    if (textured_) reserveOnHugePages(sourceUv_, positions);
  }

  // Textured: whether the mesh keeps texture coordinates (as constructed), a template argument
  // so that the loops of a mesh without them test nothing more than before they were read.
  template <bool Textured>
  uint32_t idOf(uint32_t position, uint32_t normal, uint32_t uv) {
    if (!smooth_) normal = 0;
    if (!Textured) uv = 0;
    uint32_t& first = firstId_[position];
    if (first == kUnseen) {
      first = add(position, normal, uv);
      if (smooth_) firstNormal_[position] = normal;
      if (Textured) firstUv_[position] = uv;
      return first;
    }
    if ((!smooth_ || firstNormal_[position] == normal) && (!Textured || firstUv_[position] == uv)) {
      return first;
    }
    const auto [it, inserted] = others_.try_emplace(Corner{position, normal, uv}, 0);
    if (inserted) it->second = add(position, normal, uv);
    return it->second;
  }

  // Whether output vertex i is input position i for every i: the positions array is then
  // the output as it stands.
  bool isIdentity(size_t positions) const {
    return identity_ && sourcePosition_.size() == positions;
  }
  const std::vector<uint32_t>& sourcePosition() const { return sourcePosition_; }
  const std::vector<uint32_t>& sourceNormal() const { return sourceNormal_; }
  const std::vector<uint32_t>& sourceUv() const { return sourceUv_; }

 private:
  static constexpr uint32_t kUnseen = 0xffffffffu;

  struct Corner {
    uint32_t position, normal, uv;
    bool operator==(const Corner&) const = default;
  };
  struct CornerHash {
    size_t operator()(const Corner& c) const {
      const uint64_t key = (uint64_t{c.position} << 32) | c.normal;
      return std::hash<uint64_t>{}(key ^ (uint64_t{c.uv} * 0x9e3779b97f4a7c15ull));
    }
  };

  uint32_t add(uint32_t position, uint32_t normal, uint32_t uv) {
    const auto id = static_cast<uint32_t>(sourcePosition_.size());
    identity_ = identity_ && id == position;
    sourcePosition_.push_back(position);
    if (smooth_) sourceNormal_.push_back(normal);
    if (textured_) sourceUv_.push_back(uv);
    return id;
  }

  bool smooth_;
  bool textured_;
  bool identity_ = true;
  std::vector<uint32_t> firstId_;
  std::vector<uint32_t> firstNormal_;
  std::vector<uint32_t> firstUv_;
  std::unordered_map<Corner, uint32_t, CornerHash> others_;
  std::vector<uint32_t> sourcePosition_;
  std::vector<uint32_t> sourceNormal_;
  std::vector<uint32_t> sourceUv_;
};

// Counts, checks the memory limit, reads the material libraries, then parses every piece into
// arrays of the counted sizes.
ObjArrays readPieces(std::string_view text, const std::string& path, const FileLoc& referencedFrom,
                     const MemoryLimit& limit, size_t pieceBytes, ObjMaterials& materials) {
  const std::vector<std::string_view> pieces =
      splitAtLineEnds(text, pieceBytes ? pieceBytes : kPieceBytes);
  std::vector<ObjChunkSurvey> surveys(pieces.size());
  parallelFor(pieces.size(), 0, [&](uint64_t i) { surveys[i] = countObjChunk(pieces[i]); });

  // What the pieces before each one hold: where its output starts.
  std::vector<ObjChunkCounts> before(pieces.size());
  ObjChunkCounts total;
  for (size_t i = 0; i < pieces.size(); ++i) {
    const ObjChunkCounts& counts = surveys[i].counts;
    before[i] = total;
    total.lines += counts.lines;
    total.positions += counts.positions;
    total.normals += counts.normals;
    total.faces += counts.faces;
    total.corners += counts.corners;
    total.triangles += counts.triangles;
    total.uvs += counts.uvs;
    total.materialUses += counts.materialUses;
  }
  const bool withMaterials = total.materialUses > 0;
  const uint64_t needed =
      saturatingAdd(objReadBytes(text.size(), total.positions, total.normals, total.uvs,
                                 total.corners, total.faces, total.triangles, withMaterials),
                    meshBuildBytes(total.triangles, total.positions));
  if (needed > limit.bytes || total.positions > 0xfffffffeu || total.normals > 0xfffffffeu ||
      total.uvs > 0xfffffffeu) {
    throw SceneError(referencedFrom.file.empty() ? FileLoc{path, 0, 0} : referencedFrom,
                     memoryRefusal("mesh file '" + path + "' (" + std::to_string(total.triangles) +
                                       " triangles, " + std::to_string(total.positions) +
                                       " vertices) read and built",
                                   needed, limit, "simplify the mesh or raise --memory-limit"));
  }

  // The libraries, in file order, then the material in force where each piece starts: the
  // last 'usemtl' of the pieces before it.
  for (size_t i = 0; i < pieces.size(); ++i) {
    for (const ObjLibraryLine& library : surveys[i].libraries) {
      materials.readLibraries(library.names, before[i].lines + library.line, library.column);
    }
  }
  std::vector<uint32_t> materialAtStart(pieces.size(), kDefaultFaceMaterial);
  uint32_t material = kDefaultFaceMaterial;
  for (size_t i = 0; i < pieces.size(); ++i) {
    materialAtStart[i] = material;
    if (surveys[i].counts.materialUses > 0) {
      material = materials.names().find(surveys[i].lastMaterial);
    }
  }

  ObjArrays arrays;
  sizeOnHugePages(arrays.positions, total.positions);
  sizeOnHugePages(arrays.normals, total.normals);
  sizeOnHugePages(arrays.uvs, total.uvs);
  sizeOnHugePages(arrays.cornerVertex, total.corners);
  if (total.normals > 0) sizeOnHugePages(arrays.cornerNormal, total.corners);
  if (total.uvs > 0) sizeOnHugePages(arrays.cornerUv, total.corners);
  sizeOnHugePages(arrays.faceCorners, total.faces);
  if (withMaterials) sizeOnHugePages(arrays.faceMaterial, total.faces);
  std::vector<ObjChunkResult> results(pieces.size());
  parallelFor(pieces.size(), 0, [&](uint64_t i) {
    ObjChunkTarget target;
    target.positions = arrays.positions.data() + before[i].positions;
    target.normals = arrays.normals.data() + before[i].normals;
    target.uvs = arrays.uvs.data() + before[i].uvs;
    target.cornerVertex = arrays.cornerVertex.data() + before[i].corners;
    target.cornerNormal =
        total.normals > 0 ? arrays.cornerNormal.data() + before[i].corners : nullptr;
    target.cornerUv = total.uvs > 0 ? arrays.cornerUv.data() + before[i].corners : nullptr;
    target.faceCorners = arrays.faceCorners.data() + before[i].faces;
    target.faceMaterial = withMaterials ? arrays.faceMaterial.data() + before[i].faces : nullptr;
    target.positionsBefore = before[i].positions;
    target.normalsBefore = before[i].normals;
    target.uvsBefore = before[i].uvs;
    target.positionsInFile = total.positions;
    target.normalsInFile = total.normals;
    target.uvsInFile = total.uvs;
    target.firstLine = before[i].lines + 1;
    target.materialAtStart = materialAtStart[i];
    target.materials = &materials.names();
    results[i] = parseObjChunk(pieces[i], target);
  });
  // The first error in the file: each piece stopped at its own first.
  for (ObjChunkResult& result : results) {
    if (!result.message.empty()) {
      throw SceneError(FileLoc{path, static_cast<int>(result.line), result.column}, result.message);
    }
    arrays.cornerWithoutNormal = arrays.cornerWithoutNormal || result.cornerWithoutNormal;
    arrays.cornerWithUv = arrays.cornerWithUv || result.cornerWithUv;
    if (arrays.firstLineWithoutUv == 0) arrays.firstLineWithoutUv = result.firstLineWithoutUv;
    for (ObjUnknownMaterial& unknown : result.unknownMaterials) {
      arrays.unknownMaterials.push_back(std::move(unknown));
    }
  }
  return arrays;
}

// Whether the mesh keeps vertex normals: every corner names one, and every one it names can be
// normalised (UsableNormal.h).
bool keepsNormals(const ObjArrays& arrays) {
  if (arrays.normals.empty() || arrays.cornerWithoutNormal) return false;
  std::vector<uint8_t> usable(arrays.normals.size());
  for (size_t i = 0; i < usable.size(); ++i) usable[i] = isUsableNormal(arrays.normals[i]);
  for (const uint32_t n : arrays.cornerNormal) {
    if (!usable[n]) return false;
  }
  return true;
}

// The material of each face, as the model numbers them: where every face has the same one it
// becomes the mesh's material and faceMaterials stays empty.
void assignFaceMaterials(MeshDesc& mesh, std::vector<MaterialId> perTriangle) {
  if (perTriangle.empty()) return;
  const MaterialId first = perTriangle.front();
  if (std::all_of(perTriangle.begin(), perTriangle.end(),
                  [&](MaterialId id) { return id == first; })) {
    mesh.material = first;
    return;
  }
  mesh.faceMaterials = std::move(perTriangle);
}

// materialIndex: each material number's index in the model, kDefaultFaceMaterial's last; empty
// where the model has no materials.
MeshDesc buildMesh(ObjArrays& arrays, const std::string& path, const FileLoc& referencedFrom,
                   const std::vector<MaterialId>& materialIndex) {
  MeshDesc result;
  result.source = path;
  result.loc = referencedFrom;
  const bool smooth = keepsNormals(arrays);
  const bool textured = arrays.cornerWithUv;
  const bool withMaterials = !materialIndex.empty();
  VertexNumbering numbering(arrays.positions.size(), smooth, textured);
  const auto normalAt = [&](size_t corner) { return smooth ? arrays.cornerNormal[corner] : 0; };
  const auto idOf = [&](size_t corner) {
    const uint32_t position = arrays.cornerVertex[corner];
    return textured ? numbering.idOf<true>(position, normalAt(corner), arrays.cornerUv[corner])
                    : numbering.idOf<false>(position, normalAt(corner), 0);
  };
  const auto materialOf = [&](size_t face) {
    const uint32_t n = arrays.faceMaterial[face];
    return materialIndex[n == kDefaultFaceMaterial ? materialIndex.size() - 1 : n];
  };
  std::vector<MaterialId> faceMaterials;
  const bool allTriangles = std::all_of(arrays.faceCorners.begin(), arrays.faceCorners.end(),
                                        [](uint8_t corners) { return corners == 3; });
  if (allTriangles) {
    // Each corner becomes one index where it stands: the corner array is the index array.
    if (textured) {
      for (size_t k = 0; k < arrays.cornerVertex.size(); ++k) {
        arrays.cornerVertex[k] =
            numbering.idOf<true>(arrays.cornerVertex[k], normalAt(k), arrays.cornerUv[k]);
      }
    } else {
      for (size_t k = 0; k < arrays.cornerVertex.size(); ++k) {
        arrays.cornerVertex[k] = numbering.idOf<false>(arrays.cornerVertex[k], normalAt(k), 0);
      }
    }
    result.indices = std::move(arrays.cornerVertex);
    if (withMaterials) {
      faceMaterials.resize(arrays.faceCorners.size());
      for (size_t f = 0; f < faceMaterials.size(); ++f) faceMaterials[f] = materialOf(f);
    }
  } else {
    size_t triangles = 0;
    for (const uint8_t corners : arrays.faceCorners) triangles += corners - 2u;
    reserveOnHugePages(result.indices, 3 * triangles);
    if (withMaterials) faceMaterials.reserve(triangles);
    std::vector<Vec3> polygon;
    size_t first = 0;
    for (size_t f = 0; f < arrays.faceCorners.size(); ++f) {
      const uint8_t corners = arrays.faceCorners[f];
      const auto corner = [&](size_t k) { return idOf(first + k); };
      if (corners == 3) {
        for (size_t k = 0; k < 3; ++k) result.indices.push_back(corner(k));
      } else {
        polygon.clear();
        for (size_t k = 0; k < corners; ++k) {
          polygon.push_back(arrays.positions[arrays.cornerVertex[first + k]]);
        }
        for (const uint32_t local : triangulatePolygon(polygon)) {
          result.indices.push_back(corner(local));
        }
      }
      if (withMaterials) faceMaterials.resize(result.indices.size() / 3, materialOf(f));
      first += corners;
    }
    std::vector<uint32_t>().swap(arrays.cornerVertex);
  }
  std::vector<uint32_t>().swap(arrays.cornerNormal);
  std::vector<uint32_t>().swap(arrays.cornerUv);

  if (numbering.isIdentity(arrays.positions.size())) {
    result.positions = std::move(arrays.positions);
  } else {
    const std::vector<uint32_t>& source = numbering.sourcePosition();
    reserveOnHugePages(result.positions, source.size());
    for (const uint32_t p : source) result.positions.push_back(arrays.positions[p]);
  }
  if (smooth) {
    reserveOnHugePages(result.normals, result.positions.size());
    for (const uint32_t n : numbering.sourceNormal()) {
      result.normals.push_back(glm::normalize(arrays.normals[n]));
    }
  }
  if (textured) {
    // A corner without a texture coordinate, in a mesh whose other corners have them, reads
    // the texture at (0, 0).
    reserveOnHugePages(result.uvs, result.positions.size());
    for (const uint32_t t : numbering.sourceUv()) {
      result.uvs.push_back(t == kNoUv ? Vec2(0.0f) : arrays.uvs[t]);
    }
  }
  if (result.indices.empty()) throw SceneError(FileLoc{path, 0, 0}, "mesh file has no triangles");
  assignFaceMaterials(result, std::move(faceMaterials));
  return result;
}

// The model's materials: those faces use, where some face uses one a library defines; none
// otherwise (the scene's material then covers the mesh, as for a file without materials).
std::vector<MaterialId> chooseMaterials(const ObjArrays& arrays, const ObjMaterials& materials,
                                        ModelDesc& model, const MemoryLimit& limit) {
  if (arrays.faceMaterial.empty()) return {};
  std::vector<bool> used(materials.names().size(), false);
  bool defaultUsed = false;
  bool anyDefined = false;
  for (const uint32_t n : arrays.faceMaterial) {
    if (n == kDefaultFaceMaterial) {
      defaultUsed = true;
    } else if (!used[n]) {
      used[n] = true;
      anyDefined = true;
    }
  }
  if (!anyDefined) return {};
  return materials.addUsed(used, defaultUsed, model, limit);
}

// Warnings about the faces: 'usemtl' names no library defines, corners without texture
// coordinates beside corners with them.
void warnAboutFaces(const ObjArrays& arrays, const ObjMaterials& materials, const std::string& path,
                    ModelDesc& model) {
  if (!arrays.unknownMaterials.empty()) {
    std::vector<std::string> names;
    for (const ObjUnknownMaterial& unknown : arrays.unknownMaterials) {
      if (std::find(names.begin(), names.end(), unknown.name) == names.end()) {
        names.push_back(unknown.name);
      }
    }
    const ObjUnknownMaterial& first = arrays.unknownMaterials.front();
    std::string warning = path + ":" + std::to_string(first.line) + ": usemtl '" +
                          printableExcerpt(first.name, 200) + "' names no material ";
    warning += materials.anyLibraryRead() ? "the material libraries define"
                                          : "(no material library was read)";
    if (names.size() > 1)
      warning += ", nor do " + std::to_string(names.size() - 1) + " other names";
    warning += "; their faces get the default material";
    model.warnings.push_back(std::move(warning));
  }
  if (arrays.cornerWithUv && arrays.firstLineWithoutUv > 0) {
    model.warnings.push_back(path + ":" + std::to_string(arrays.firstLineWithoutUv) +
                             ": face corners without texture coordinates beside corners with "
                             "them; they read textures at (0, 0)");
  }
}

ModelDesc readModel(std::string_view text, const std::string& path, const FileLoc& referencedFrom,
                    const MemoryLimit& limit, size_t pieceBytes, const CompanionFiles& files,
                    MeshFileBytes* file) {
  ModelDesc model;
  model.source = path;
  ObjMaterials materials(path, files, model.warnings);
  ObjArrays arrays = readPieces(text, path, referencedFrom, limit, pieceBytes, materials);
  if (file) file->release();  // the text is read: its pages go before the mesh is assembled
  warnAboutFaces(arrays, materials, path, model);
  const std::vector<MaterialId> materialIndex = chooseMaterials(arrays, materials, model, limit);
  model.meshes.push_back(buildMesh(arrays, path, referencedFrom, materialIndex));
  return model;
}

}  // namespace

ModelDesc loadObjModel(const std::string& path, const FileLoc& referencedFrom,
                       const MemoryLimit& limit, const CompanionFiles& files) {
  MeshFileBytes file(path, referencedFrom, limit);
  return readModel(file.bytes(), path, referencedFrom, limit, 0, files, &file);
}

ModelDesc parseObjModel(std::string_view text, const std::string& path,
                        const FileLoc& referencedFrom, const MemoryLimit& limit, size_t pieceBytes,
                        const CompanionFiles& files) {
  return readModel(text, path, referencedFrom, limit, pieceBytes, files, nullptr);
}

}  // namespace prism

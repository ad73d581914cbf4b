// OBJ meshes, read on several threads. The text is cut at line ends (LineChunks.h); each piece is
// counted, then parsed straight into arrays shared by all pieces (ObjChunk.h), in file order,
// so the result is the same however the text is cut. What is read: 'v' positions, 'vn' normals
// and 'f' faces (v, v/vt, v//vn, v/vt/vn corners; negative indices count back from the
// statement). Everything else ('vt', 'g', 'o', 's', 'usemtl', 'mtllib', 'l', 'p', ...) is
// skipped: the scene assigns the material. Faces of four or more corners are ear-clipped by
// PolygonTriangulator, as NFF polygons are.
#include "parse/ObjLoader.h"

#include <algorithm>
#include <unordered_map>

#include "parse/LineChunks.h"
#include "parse/MeshFileBytes.h"
#include "parse/ObjChunk.h"
#include "parse/PolygonTriangulator.h"
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
  std::vector<uint32_t> cornerVertex;
  std::vector<uint32_t> cornerNormal;  // empty when the file has no normals
  std::vector<uint8_t> faceCorners;
  bool cornerWithoutNormal = false;
};

// One output vertex per distinct (position, normal) pair, numbered in the order the corners
// first use them, so normals can be indexed like positions. Most positions come with one normal
// (or none): the first pair of each position is kept in flat arrays and only the others in a map.
class VertexNumbering {
 public:
  VertexNumbering(size_t positions, bool smooth) : smooth_(smooth), firstId_(positions, kUnseen) {
    if (smooth_) firstNormal_.resize(positions);
    reserveOnHugePages(sourcePosition_, positions);
    if (smooth_) reserveOnHugePages(sourceNormal_, positions);
  }

  uint32_t idOf(uint32_t position, uint32_t normal) {
    if (!smooth_) normal = 0;
    uint32_t& first = firstId_[position];
    if (first == kUnseen) {
      first = add(position, normal);
      if (smooth_) firstNormal_[position] = normal;
      return first;
    }
    if (!smooth_ || firstNormal_[position] == normal) return first;
    const uint64_t key = (uint64_t{position} << 32) | normal;
    const auto [it, inserted] = others_.try_emplace(key, 0);
    if (inserted) it->second = add(position, normal);
    return it->second;
  }

  // Whether output vertex i is input position i for every i: the positions array is then
  // the output as it stands.
  bool isIdentity(size_t positions) const {
    return identity_ && sourcePosition_.size() == positions;
  }
  const std::vector<uint32_t>& sourcePosition() const { return sourcePosition_; }
  const std::vector<uint32_t>& sourceNormal() const { return sourceNormal_; }

 private:
  static constexpr uint32_t kUnseen = 0xffffffffu;

  uint32_t add(uint32_t position, uint32_t normal) {
    const auto id = static_cast<uint32_t>(sourcePosition_.size());
    identity_ = identity_ && id == position;
    sourcePosition_.push_back(position);
    if (smooth_) sourceNormal_.push_back(normal);
    return id;
  }

  bool smooth_;
  bool identity_ = true;
  std::vector<uint32_t> firstId_;
  std::vector<uint32_t> firstNormal_;
  std::unordered_map<uint64_t, uint32_t> others_;
  std::vector<uint32_t> sourcePosition_;
  std::vector<uint32_t> sourceNormal_;
};

// Counts, checks the memory limit, then parses every piece into arrays of the counted sizes.
ObjArrays readPieces(std::string_view text, const std::string& path, const FileLoc& referencedFrom,
                     const MemoryLimit& limit, size_t pieceBytes) {
  const std::vector<std::string_view> pieces =
      splitAtLineEnds(text, pieceBytes ? pieceBytes : kPieceBytes);
  std::vector<ObjChunkCounts> counts(pieces.size());
  parallelFor(pieces.size(), 0, [&](uint64_t i) { counts[i] = countObjChunk(pieces[i]); });

  // What the pieces before each one hold: where its output starts.
  std::vector<ObjChunkCounts> before(pieces.size());
  ObjChunkCounts total;
  for (size_t i = 0; i < pieces.size(); ++i) {
    before[i] = total;
    total.lines += counts[i].lines;
    total.positions += counts[i].positions;
    total.normals += counts[i].normals;
    total.faces += counts[i].faces;
    total.corners += counts[i].corners;
    total.triangles += counts[i].triangles;
  }
  const uint64_t needed = saturatingAdd(objReadBytes(text.size(), total.positions, total.normals,
                                                     total.corners, total.faces, total.triangles),
                                        meshBuildBytes(total.triangles, total.positions));
  if (needed > limit.bytes || total.positions > 0xfffffffeu || total.normals > 0xfffffffeu) {
    throw SceneError(referencedFrom.file.empty() ? FileLoc{path, 0, 0} : referencedFrom,
                     memoryRefusal("mesh file '" + path + "' (" + std::to_string(total.triangles) +
                                       " triangles, " + std::to_string(total.positions) +
                                       " vertices) read and built",
                                   needed, limit, "simplify the mesh or raise --memory-limit"));
  }

  ObjArrays arrays;
  sizeOnHugePages(arrays.positions, total.positions);
  sizeOnHugePages(arrays.normals, total.normals);
  sizeOnHugePages(arrays.cornerVertex, total.corners);
  if (total.normals > 0) sizeOnHugePages(arrays.cornerNormal, total.corners);
  sizeOnHugePages(arrays.faceCorners, total.faces);
  std::vector<ObjChunkResult> results(pieces.size());
  parallelFor(pieces.size(), 0, [&](uint64_t i) {
    ObjChunkTarget target;
    target.positions = arrays.positions.data() + before[i].positions;
    target.normals = arrays.normals.data() + before[i].normals;
    target.cornerVertex = arrays.cornerVertex.data() + before[i].corners;
    target.cornerNormal =
        total.normals > 0 ? arrays.cornerNormal.data() + before[i].corners : nullptr;
    target.faceCorners = arrays.faceCorners.data() + before[i].faces;
    target.positionsBefore = before[i].positions;
    target.normalsBefore = before[i].normals;
    target.positionsInFile = total.positions;
    target.normalsInFile = total.normals;
    target.firstLine = before[i].lines + 1;
    results[i] = parseObjChunk(pieces[i], target);
  });
  // The first error in the file: each piece stopped at its own first.
  for (const ObjChunkResult& result : results) {
    if (!result.message.empty()) {
      throw SceneError(FileLoc{path, static_cast<int>(result.line), result.column}, result.message);
    }
    arrays.cornerWithoutNormal = arrays.cornerWithoutNormal || result.cornerWithoutNormal;
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

MeshDesc buildMesh(ObjArrays& arrays, const std::string& path, const FileLoc& referencedFrom) {
  MeshDesc result;
  result.source = path;
  result.loc = referencedFrom;
  const bool smooth = keepsNormals(arrays);
  VertexNumbering numbering(arrays.positions.size(), smooth);
  const auto normalAt = [&](size_t corner) { return smooth ? arrays.cornerNormal[corner] : 0; };
  const bool allTriangles = std::all_of(arrays.faceCorners.begin(), arrays.faceCorners.end(),
                                        [](uint8_t corners) { return corners == 3; });
  if (allTriangles) {
    // Each corner becomes one index where it stands: the corner array is the index array.
    for (size_t k = 0; k < arrays.cornerVertex.size(); ++k) {
      arrays.cornerVertex[k] = numbering.idOf(arrays.cornerVertex[k], normalAt(k));
    }
    result.indices = std::move(arrays.cornerVertex);
  } else {
    size_t triangles = 0;
    for (const uint8_t corners : arrays.faceCorners) triangles += corners - 2u;
    reserveOnHugePages(result.indices, 3 * triangles);
    std::vector<Vec3> polygon;
    size_t first = 0;
    for (const uint8_t corners : arrays.faceCorners) {
      const auto corner = [&](size_t k) {
        return numbering.idOf(arrays.cornerVertex[first + k], normalAt(first + k));
      };
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
      first += corners;
    }
    std::vector<uint32_t>().swap(arrays.cornerVertex);
  }
  std::vector<uint32_t>().swap(arrays.cornerNormal);

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
  if (result.indices.empty()) throw SceneError(FileLoc{path, 0, 0}, "mesh file has no triangles");
  return result;
}

}  // namespace

MeshDesc loadObjMesh(const std::string& path, const FileLoc& referencedFrom,
                     const MemoryLimit& limit) {
  MeshFileBytes file(path, referencedFrom, limit);
  ObjArrays arrays = readPieces(file.bytes(), path, referencedFrom, limit, 0);
  file.release();  // the text is read: its pages go before the mesh is assembled
  return buildMesh(arrays, path, referencedFrom);
}

MeshDesc parseObjMesh(std::string_view text, const std::string& path, const FileLoc& referencedFrom,
                      const MemoryLimit& limit, size_t pieceBytes) {
  ObjArrays arrays = readPieces(text, path, referencedFrom, limit, pieceBytes);
  return buildMesh(arrays, path, referencedFrom);
}

}  // namespace prism

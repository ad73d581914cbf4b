// One piece of an OBJ file (parse/LineChunks.h), read in two passes so that many pieces can be
// read at once and their results land in shared arrays without a copy: the first pass counts
// what the piece holds, which tells every piece where its output starts; the second parses it
// there. Both passes see the same lines the same way (a statement is its first word: "v", "vn",
// "vt", "f", "usemtl" or "mtllib"; words are separated by blanks, and one that starts with '#'
// ends the line), so the counts always match what the second pass writes.
//
// Materials cross the cuts: a face takes the material of the last 'usemtl' before it, which may
// lie in an earlier piece. The first pass notes each piece's last 'usemtl' (and its 'mtllib'
// lines, read before any face), so the material in force at each piece's start is known before
// the second pass begins.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "math/Vec.h"

namespace prism {

struct ObjChunkCounts {
  uint64_t lines = 0;         // as tinyobjloader counted them: \n, \r\n or a lone \r end a line
  uint64_t positions = 0;     // 'v' statements
  uint64_t normals = 0;       // 'vn' statements
  uint64_t faces = 0;         // 'f' statements
  uint64_t corners = 0;       // words of the 'f' statements
  uint64_t triangles = 0;     // corners - 2 for each face of three or more
  uint64_t uvs = 0;           // 'vt' statements
  uint64_t materialUses = 0;  // 'usemtl' statements
};

// A 'mtllib' line: its names, and where in the piece they start.
struct ObjLibraryLine {
  uint64_t line = 0;  // within the piece, from 1
  int column = 0;
  std::string_view names;  // the rest of the line, blanks trimmed, a trailing comment dropped
};

// What the first pass finds in a piece: its counts, and what the pieces must agree on before
// the second pass.
struct ObjChunkSurvey {
  ObjChunkCounts counts;
  std::vector<ObjLibraryLine> libraries;
  std::string_view lastMaterial;  // the name of the piece's last 'usemtl', when it has one
};

ObjChunkSurvey countObjChunk(std::string_view text);

// The material names the model's MTL libraries define, numbered in the order they are defined;
// a face's material is one of these numbers or kDefaultFaceMaterial.
class ObjMaterialNames {
 public:
  // The number of name, numbering it next when it is new; second: whether it was.
  std::pair<uint32_t, bool> add(const std::string& name) {
    const auto [it, added] = ids_.try_emplace(name, static_cast<uint32_t>(ids_.size()));
    return {it->second, added};
  }
  // The number of name, or kDefaultFaceMaterial when no library defines it.
  uint32_t find(std::string_view name) const;
  size_t size() const { return ids_.size(); }

 private:
  struct Hash {
    using is_transparent = void;
    size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  std::unordered_map<std::string, uint32_t, Hash, std::equal_to<>> ids_;
};

// Faces before any 'usemtl', and faces whose 'usemtl' names no defined material.
inline constexpr uint32_t kDefaultFaceMaterial = 0xffffffffu;

// Where one piece writes and what it must know of the whole file to check its faces.
struct ObjChunkTarget {
  Vec3* positions = nullptr;         // the piece's first position
  Vec3* normals = nullptr;           // its first normal
  uint32_t* cornerVertex = nullptr;  // its first face corner: a 0-based position index
  uint32_t* cornerNormal = nullptr;  // 0-based normal index or kNoNormal; null: the file has none
  uint8_t* faceCorners = nullptr;    // corners of each face (3 to 255)
  Vec2* uvs = nullptr;               // its first texture coordinate
  uint32_t* cornerUv = nullptr;      // 0-based 'vt' index or kNoUv; null: the file has no 'vt'
  uint32_t* faceMaterial = nullptr;  // each face's material; null: the file has no 'usemtl'
  uint64_t positionsBefore = 0;      // in the pieces before this one (for relative indices)
  uint64_t normalsBefore = 0;
  uint64_t uvsBefore = 0;
  uint64_t positionsInFile = 0;
  uint64_t normalsInFile = 0;
  uint64_t uvsInFile = 0;
  uint64_t firstLine = 1;  // the piece's first line in the file
  // The material in force where the piece starts (the last 'usemtl' before it), and the names
  // its own 'usemtl' lines may use.
  uint32_t materialAtStart = kDefaultFaceMaterial;
  const ObjMaterialNames* materials = nullptr;
};

inline constexpr uint32_t kNoNormal = 0xffffffffu;
inline constexpr uint32_t kNoUv = 0xffffffffu;

// A 'usemtl' whose name no library defines.
struct ObjUnknownMaterial {
  uint64_t line = 0;
  std::string name;
};

struct ObjChunkResult {
  bool cornerWithoutNormal = false;  // some face corner names no normal
  bool cornerWithUv = false;         // some face corner names a texture coordinate
  uint64_t firstLineWithoutUv = 0;   // where a face corner first names none (0: nowhere)
  std::vector<ObjUnknownMaterial> unknownMaterials;
  // The piece's first error (the parse stops there); empty message: none.
  uint64_t line = 0;
  int column = 0;
  std::string message;
};

// The second pass: parses text, whose counts must be those countObjChunk gave, into target.
ObjChunkResult parseObjChunk(std::string_view text, const ObjChunkTarget& target);

}  // namespace prism

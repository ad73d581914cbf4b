// One piece of an OBJ file (parse/LineChunks.h), read in two passes so that many pieces can be
// read at once and their results land in shared arrays without a copy: the first pass counts
// what the piece holds, which tells every piece where its output starts; the second parses it
// there. Both passes see the same lines the same way (a statement is its first word: "v", "vn"
// or "f"; words are separated by blanks, and one that starts with '#' ends the line), so the
// counts always match what the second pass writes.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "math/Vec.h"

namespace prism {

struct ObjChunkCounts {
  uint64_t lines = 0;      // as tinyobjloader counted them: \n, \r\n or a lone \r end a line
  uint64_t positions = 0;  // 'v' statements
  uint64_t normals = 0;    // 'vn' statements
  uint64_t faces = 0;      // 'f' statements
  uint64_t corners = 0;    // words of the 'f' statements
  uint64_t triangles = 0;  // corners - 2 for each face of three or more
};

ObjChunkCounts countObjChunk(std::string_view text);

// Where one piece writes and what it must know of the whole file to check its faces.
struct ObjChunkTarget {
  Vec3* positions = nullptr;         // the piece's first position
  Vec3* normals = nullptr;           // its first normal
  uint32_t* cornerVertex = nullptr;  // its first face corner: a 0-based position index
  uint32_t* cornerNormal = nullptr;  // 0-based normal index or kNoNormal; null: the file has none
  uint8_t* faceCorners = nullptr;    // corners of each face (3 to 255)
  uint64_t positionsBefore = 0;      // in the pieces before this one (for relative indices)
  uint64_t normalsBefore = 0;
  uint64_t positionsInFile = 0;
  uint64_t normalsInFile = 0;
  uint64_t firstLine = 1;  // the piece's first line in the file
};

inline constexpr uint32_t kNoNormal = 0xffffffffu;

struct ObjChunkResult {
  bool cornerWithoutNormal = false;  // some face corner names no normal
  // The piece's first error (the parse stops there); empty message: none.
  uint64_t line = 0;
  int column = 0;
  std::string message;
};

// The second pass: parses text, whose counts must be those countObjChunk gave, into target.
ObjChunkResult parseObjChunk(std::string_view text, const ObjChunkTarget& target);

}  // namespace prism

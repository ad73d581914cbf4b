#include "parse/ObjChunk.h"

#include <charconv>
#include <cmath>

#include "parse/LineChunks.h"
#include "parse/PrintableText.h"

namespace prism {

namespace {

bool isBlank(char c) {
  return c == ' ' || c == '\t';
}
bool isLineEnd(char c) {
  return c == '\n' || c == '\r';
}

const char* skipBlanks(const char* p, const char* end) {
  while (p < end && isBlank(*p)) ++p;
  return p;
}
const char* wordEnd(const char* p, const char* end) {
  while (p < end && !isBlank(*p) && !isLineEnd(*p)) ++p;
  return p;
}
// The start of the next word on this line, or null where the line (or a comment) begins.
const char* nextWord(const char* p, const char* end) {
  p = skipBlanks(p, end);
  return (p == end || isLineEnd(*p) || *p == '#') ? nullptr : p;
}

enum class Statement { Position, Normal, Face, Other };

Statement statementOf(const char* word, const char* end) {
  const size_t n = static_cast<size_t>(end - word);
  if (n == 1 && word[0] == 'v') return Statement::Position;
  if (n == 2 && word[0] == 'v' && word[1] == 'n') return Statement::Normal;
  if (n == 1 && word[0] == 'f') return Statement::Face;
  return Statement::Other;
}

// An error at a word of the current line; the parse stops at the first.
struct ParseFailure {
  const char* at;
  std::string message;
};

// Reads an OBJ coordinate: a whole word that std::from_chars reads as a double (after an
// optional '+'), finite as a float. The double is rounded to float as tinyobjloader did.
float coordinate(const char* word, const char* end) {
  const std::string_view w(word, static_cast<size_t>(end - word));
  double value = 0.0;
  const char* first = word + (*word == '+' ? 1 : 0);
  const auto [ptr, ec] = std::from_chars(first, end, value);
  const float rounded = static_cast<float>(value);
  if (ec == std::errc::result_out_of_range ||
      (ec == std::errc() && ptr == end && !std::isfinite(rounded))) {
    throw ParseFailure{word, "non-finite coordinate '" + printableExcerpt(w) + "'"};
  }
  if (ec != std::errc() || ptr != end) {
    throw ParseFailure{word, "expected a number but found '" + printableExcerpt(w) + "'"};
  }
  return rounded;
}

// The numbers of a 'v' or 'vn' line (all must be numbers; the first three are kept).
Vec3 threeCoordinates(const char* statement, const char* p, const char* end, const char* what) {
  float xyz[3] = {0, 0, 0};
  int count = 0;
  while (const char* word = nextWord(p, end)) {
    p = wordEnd(word, end);
    const float value = coordinate(word, p);
    if (count < 3) xyz[count] = value;
    ++count;
  }
  if (count < 3) throw ParseFailure{statement, std::string(what) + " needs 3 coordinates"};
  return Vec3(xyz[0], xyz[1], xyz[2]);
}

// An OBJ index: an optional sign and digits. Values past any file's size are kept large rather
// than overflowing. False where there are no digits.
bool readIndex(const char*& p, const char* end, int64_t& value) {
  const bool negative = p < end && *p == '-';
  if (p < end && (*p == '-' || *p == '+')) ++p;
  const char* digits = p;
  value = 0;
  while (p < end && static_cast<unsigned>(*p - '0') < 10) {
    if (value < (int64_t{1} << 40)) value = value * 10 + (*p - '0');
    ++p;
  }
  if (negative) value = -value;
  return p != digits;
}

// A 0-based index into `inFile` items from the OBJ index `index` (1-based, or negative: relative
// to the `before` items read so far).
uint32_t resolveIndex(int64_t index, uint64_t before, uint64_t inFile, const char* word,
                      const char* what) {
  const std::string shown = std::to_string(index);
  if (index == 0) {
    throw ParseFailure{word, std::string("face refers to ") + what + " 0 (OBJ counts from 1)"};
  }
  if (index > 0) {
    if (static_cast<uint64_t>(index) > inFile) {
      throw ParseFailure{word, std::string("face refers to ") + what + " " + shown +
                                   " but the file has " + std::to_string(inFile)};
    }
    return static_cast<uint32_t>(index - 1);
  }
  if (static_cast<uint64_t>(-index) > before) {
    throw ParseFailure{word, std::string("face refers to ") + what + " " + shown + " but only " +
                                 std::to_string(before) + " come before it"};
  }
  return static_cast<uint32_t>(static_cast<int64_t>(before) + index);
}

}  // namespace

ObjChunkCounts countObjChunk(std::string_view text) {
  ObjChunkCounts counts;
  const char* p = text.data();
  const char* const end = p + text.size();
  while (p < end) {
    ++counts.lines;
    if (const char* word = nextWord(p, end)) {
      p = wordEnd(word, end);
      switch (statementOf(word, p)) {
        case Statement::Position:
          ++counts.positions;
          break;
        case Statement::Normal:
          ++counts.normals;
          break;
        case Statement::Face: {
          uint64_t corners = 0;
          while (const char* corner = nextWord(p, end)) {
            p = wordEnd(corner, end);
            ++corners;
          }
          ++counts.faces;
          counts.corners += corners;
          if (corners >= 3) counts.triangles += corners - 2;
          break;
        }
        case Statement::Other:
          break;
      }
    }
    p = nextLineStart(p, end);
  }
  return counts;
}

ObjChunkResult parseObjChunk(std::string_view text, const ObjChunkTarget& target) {
  ObjChunkResult result;
  const char* p = text.data();
  const char* const end = p + text.size();
  uint64_t line = target.firstLine - 1;
  const char* lineStart = p;
  Vec3* position = target.positions;
  Vec3* normal = target.normals;
  uint32_t* cornerVertex = target.cornerVertex;
  uint32_t* cornerNormal = target.cornerNormal;
  uint8_t* faceCorners = target.faceCorners;
  try {
    while (p < end) {
      ++line;
      lineStart = p;
      if (const char* word = nextWord(p, end)) {
        p = wordEnd(word, end);
        switch (statementOf(word, p)) {
          case Statement::Position:
            *position++ = threeCoordinates(word, p, end, "vertex");
            break;
          case Statement::Normal:
            *normal++ = threeCoordinates(word, p, end, "normal");
            break;
          case Statement::Face: {
            const uint64_t positionsBefore =
                target.positionsBefore + static_cast<uint64_t>(position - target.positions);
            const uint64_t normalsBefore =
                target.normalsBefore + static_cast<uint64_t>(normal - target.normals);
            const char* face = word;
            int corners = 0;
            while (const char* corner = nextWord(p, end)) {
              p = wordEnd(corner, end);
              // v, v/vt, v//vn or v/vt/vn; vt is checked for form and ignored.
              const char* q = corner;
              int64_t v = 0, vt = 0, vn = 0;
              bool hasNormal = false;
              bool ok = readIndex(q, p, v);
              if (ok && q < p && *q == '/') {
                ++q;
                if (q < p && *q != '/') {
                  ok = readIndex(q, p, vt);
                  if (ok && vt == 0) {
                    throw ParseFailure{corner,
                                       "face refers to texture coordinate 0 (OBJ counts from 1)"};
                  }
                }
                if (ok && q < p && *q == '/') {
                  ++q;
                  hasNormal = q < p;
                  if (hasNormal) ok = readIndex(q, p, vn);
                }
              }
              if (!ok || q != p) {
                throw ParseFailure{corner,
                                   "expected a face corner (v, v/vt, v//vn or v/vt/vn) "
                                   "but found '" +
                                       printableExcerpt(std::string_view(
                                           corner, static_cast<size_t>(p - corner))) +
                                       "'"};
              }
              *cornerVertex++ =
                  resolveIndex(v, positionsBefore, target.positionsInFile, corner, "vertex");
              if (hasNormal) {
                const uint32_t n =
                    resolveIndex(vn, normalsBefore, target.normalsInFile, corner, "normal");
                if (cornerNormal) *cornerNormal++ = n;
              } else {
                result.cornerWithoutNormal = true;
                if (cornerNormal) *cornerNormal++ = kNoNormal;
              }
              ++corners;
            }
            if (corners < 3) throw ParseFailure{face, "face needs at least 3 vertices"};
            if (corners > 255) throw ParseFailure{face, "face has more than 255 vertices"};
            *faceCorners++ = static_cast<uint8_t>(corners);
            break;
          }
          case Statement::Other:
            break;
        }
      }
      p = nextLineStart(p, end);
    }
  } catch (const ParseFailure& failure) {
    result.line = line;
    result.column = static_cast<int>(failure.at - lineStart) + 1;
    result.message = failure.message;
  }
  return result;
}

}  // namespace prism

#include "parse/ObjChunk.h"

#include <charconv>
#include <cmath>
#include <cstring>

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

enum class Statement { Position, Normal, TexCoord, Face, UseMaterial, MaterialLibrary, Other };

Statement statementOf(const char* word, const char* end) {
  const size_t n = static_cast<size_t>(end - word);
  if (n == 1) {
    if (word[0] == 'v') return Statement::Position;
    if (word[0] == 'f') return Statement::Face;
  } else if (n == 2 && word[0] == 'v') {
    if (word[1] == 'n') return Statement::Normal;
    if (word[1] == 't') return Statement::TexCoord;
  } else if (n == 6) {
    if (std::memcmp(word, "usemtl", 6) == 0) return Statement::UseMaterial;
    if (std::memcmp(word, "mtllib", 6) == 0) return Statement::MaterialLibrary;
  }
  return Statement::Other;
}

// The rest of the line from p, blanks trimmed at both ends and a trailing comment dropped: a
// material's name or the names of 'mtllib', which may hold blanks.
std::string_view restOfLine(const char* p, const char* end) {
  const char* first = nextWord(p, end);
  if (!first) return {};
  const char* last = first;
  while (const char* word = nextWord(p, end)) {
    p = wordEnd(word, end);
    last = p;
  }
  return std::string_view(first, static_cast<size_t>(last - first));
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

// The numbers of a 'v', 'vn' or 'vt' line (all must be numbers; the first three are kept, and
// at least `needed` must be there).
Vec3 coordinates(const char* statement, const char* p, const char* end, const char* what,
                 int needed) {
  float xyz[3] = {0, 0, 0};
  int count = 0;
  while (const char* word = nextWord(p, end)) {
    p = wordEnd(word, end);
    const float value = coordinate(word, p);
    if (count < 3) xyz[count] = value;
    ++count;
  }
  if (count < needed) {
    throw ParseFailure{statement, std::string(what) + " needs " + std::to_string(needed) +
                                      (needed == 1 ? " coordinate" : " coordinates")};
  }
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
  if (index > 0 && static_cast<uint64_t>(index) <= inFile) return static_cast<uint32_t>(index - 1);
  if (index < 0 && static_cast<uint64_t>(-index) <= before) {
    return static_cast<uint32_t>(static_cast<int64_t>(before) + index);
  }
  const std::string refers = std::string("face refers to ") + what + " " + std::to_string(index);
  if (index == 0) throw ParseFailure{word, refers + " (OBJ counts from 1)"};
  if (index > 0) throw ParseFailure{word, refers + " but the file has " + std::to_string(inFile)};
  throw ParseFailure{word, refers + " but only " + std::to_string(before) + " come before it"};
}

// The number of the material a 'usemtl' line names, or kDefaultFaceMaterial (noted in result)
// where no library defines it. Out of line: plain files never call it, and the face loop keeps
// its registers.
[[gnu::noinline]] uint32_t materialNamed(std::string_view name, uint64_t line,
                                         const ObjMaterialNames* names, ObjChunkResult& result) {
  const uint32_t material = names ? names->find(name) : kDefaultFaceMaterial;
  if (material == kDefaultFaceMaterial)
    result.unknownMaterials.push_back({line, std::string(name)});
  return material;
}

// Finds line ends with memchr where the piece has no lone \r (a \r\n's \r ends the line's last
// word, so the line runs to its \n): most files. Otherwise character by character.
class LineEnds {
 public:
  explicit LineEnds(std::string_view text) : newlinesOnly_(!hasLoneCarriageReturn(text)) {}

  // Where the line that `from` is in ends (its \n, \r\n or \r; or the end of the text).
  const char* lineEnd(const char* from, const char* end) const {
    if (newlinesOnly_) {
      const void* newline = std::memchr(from, '\n', static_cast<size_t>(end - from));
      return newline ? static_cast<const char*>(newline) : end;
    }
    while (from < end && !isLineEnd(*from)) ++from;
    return from;
  }

  const char* nextLineStart(const char* from, const char* end) const {
    // Most statements are parsed up to their line's end: no search then.
    if (from < end && *from == '\n') return from + 1;
    if (!newlinesOnly_) return prism::nextLineStart(from, end);
    return skipLineEnd(lineEnd(from, end), end);
  }

  // Past the line end at `at`.
  static const char* skipLineEnd(const char* at, const char* end) {
    if (at < end && *at == '\r' && at + 1 < end && at[1] == '\n') return at + 2;
    return at < end ? at + 1 : end;
  }

 private:
  static bool hasLoneCarriageReturn(std::string_view text) {
    const char* p = text.data();
    const char* const end = p + text.size();
    while (const void* found = std::memchr(p, '\r', static_cast<size_t>(end - p))) {
      p = static_cast<const char*>(found) + 1;
      if (p == end || *p != '\n') return true;
    }
    return false;
  }

  bool newlinesOnly_;
};

// The words in [p, end), one line's rest, as nextWord would step through them. The first pass
// reads every face line only to count them: a loop without branches, gone over again the slow
// way only where a '#' may start a comment.
uint64_t countWords(const char* p, const char* end) {
  uint64_t words = 0;
  bool inWord = false;
  bool hash = false;
  for (const char* c = p; c < end; ++c) {
    const bool blank = isBlank(*c) || *c == '\r';
    words += !inWord && !blank;
    inWord = !blank;
    hash |= *c == '#';
  }
  if (!hash) return words;
  words = 0;
  while (const char* word = nextWord(p, end)) {
    p = wordEnd(word, end);
    ++words;
  }
  return words;
}

// A face corner's indices as written, the word [corner, end): v, v/vt, v//vn or v/vt/vn.
struct Corner {
  int64_t v = 0, vt = 0, vn = 0;
  bool hasUv = false, hasNormal = false;
};

// Inlined into the face loop, which reads millions of corners.
[[gnu::always_inline]] inline Corner readCorner(const char* corner, const char* end) {
  Corner c;
  const char* q = corner;
  bool ok = readIndex(q, end, c.v);
  if (ok && q < end && *q == '/') {
    ++q;
    if (q < end && *q != '/') {
      ok = readIndex(q, end, c.vt);
      c.hasUv = true;
    }
    if (ok && q < end && *q == '/') {
      ++q;
      c.hasNormal = q < end;
      if (c.hasNormal) ok = readIndex(q, end, c.vn);
    }
  }
  if (!ok || q != end) {
    throw ParseFailure{
        corner, "expected a face corner (v, v/vt, v//vn or v/vt/vn) but found '" +
                    printableExcerpt(std::string_view(corner, static_cast<size_t>(end - corner))) +
                    "'"};
  }
  return c;
}

}  // namespace

uint32_t ObjMaterialNames::find(std::string_view name) const {
  const auto it = ids_.find(name);
  return it == ids_.end() ? kDefaultFaceMaterial : it->second;
}

ObjChunkSurvey countObjChunk(std::string_view text) {
  ObjChunkSurvey survey;
  ObjChunkCounts& counts = survey.counts;
  const LineEnds lineEnds(text);
  const char* p = text.data();
  const char* const end = p + text.size();
  while (p < end) {
    ++counts.lines;
    const char* lineStart = p;
    const char* lineEnd = lineEnds.lineEnd(p, end);
    if (const char* word = nextWord(p, lineEnd)) {
      p = wordEnd(word, lineEnd);
      switch (statementOf(word, p)) {
        case Statement::Position:
          ++counts.positions;
          break;
        case Statement::Normal:
          ++counts.normals;
          break;
        case Statement::TexCoord:
          ++counts.uvs;
          break;
        case Statement::Face: {
          const uint64_t corners = countWords(p, lineEnd);
          ++counts.faces;
          counts.corners += corners;
          if (corners >= 3) counts.triangles += corners - 2;
          break;
        }
        case Statement::UseMaterial:
          ++counts.materialUses;
          survey.lastMaterial = restOfLine(p, lineEnd);
          break;
        case Statement::MaterialLibrary: {
          const std::string_view names = restOfLine(p, lineEnd);
          const char* at = names.empty() ? word : names.data();
          survey.libraries.push_back({counts.lines, static_cast<int>(at - lineStart) + 1, names});
          break;
        }
        case Statement::Other:
          break;
      }
    }
    p = LineEnds::skipLineEnd(lineEnd, end);
  }
  return survey;
}

ObjChunkResult parseObjChunk(std::string_view text, const ObjChunkTarget& target) {
  ObjChunkResult result;
  const LineEnds lineEnds(text);
  const char* p = text.data();
  const char* const end = p + text.size();
  uint64_t line = target.firstLine - 1;
  const char* lineStart = p;
  Vec3* position = target.positions;
  Vec3* normal = target.normals;
  uint32_t* cornerVertex = target.cornerVertex;
  uint32_t* cornerNormal = target.cornerNormal;
  uint8_t* faceCorners = target.faceCorners;
  Vec2* uv = target.uvs;
  uint32_t* cornerUv = target.cornerUv;
  uint32_t* faceMaterial = target.faceMaterial;
  uint32_t material = target.materialAtStart;
  try {
    while (p < end) {
      ++line;
      lineStart = p;
      if (const char* word = nextWord(p, end)) {
        p = wordEnd(word, end);
        switch (statementOf(word, p)) {
          case Statement::Position:
            *position++ = coordinates(word, p, end, "vertex", 3);
            break;
          case Statement::Normal:
            *normal++ = coordinates(word, p, end, "normal", 3);
            break;
          case Statement::TexCoord: {
            // "vt u [v [w]]": v is 0 where it is not given; w is not used.
            const Vec3 uvw = coordinates(word, p, end, "texture coordinate", 1);
            *uv++ = Vec2(uvw.x, uvw.y);
            break;
          }
          case Statement::UseMaterial: {
            const char* lineEnd = lineEnds.lineEnd(p, end);
            material = materialNamed(restOfLine(p, lineEnd), line, target.materials, result);
            p = lineEnd;
            break;
          }
          case Statement::Face: {
            const uint64_t positionsBefore =
                target.positionsBefore + static_cast<uint64_t>(position - target.positions);
            const uint64_t normalsBefore =
                target.normalsBefore + static_cast<uint64_t>(normal - target.normals);
            const uint64_t uvsBefore = target.uvsBefore + static_cast<uint64_t>(uv - target.uvs);
            const char* face = word;
            int corners = 0;
            while (const char* corner = nextWord(p, end)) {
              p = wordEnd(corner, end);
              const auto [v, vt, vn, hasUv, hasNormal] = readCorner(corner, p);
              *cornerVertex++ =
                  resolveIndex(v, positionsBefore, target.positionsInFile, corner, "vertex");
              if (hasUv) {
                const uint32_t t =
                    resolveIndex(vt, uvsBefore, target.uvsInFile, corner, "texture coordinate");
                if (cornerUv) *cornerUv++ = t;
                result.cornerWithUv = true;
              } else if (cornerUv) {
                *cornerUv++ = kNoUv;
                if (result.firstLineWithoutUv == 0) result.firstLineWithoutUv = line;
              }
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
            if (faceMaterial) *faceMaterial++ = material;
            break;
          }
          case Statement::MaterialLibrary:  // read by the first pass
          case Statement::Other:
            break;
        }
      }
      p = lineEnds.nextLineStart(p, end);
    }
  } catch (const ParseFailure& failure) {
    result.line = line;
    result.column = static_cast<int>(failure.at - lineStart) + 1;
    result.message = failure.message;
  }
  return result;
}

}  // namespace prism

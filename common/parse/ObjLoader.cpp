// OBJ meshes through tinyobjloader. tinyobjloader reads the text; this file checks what it read
// (indices, finite numbers) and triangulates, because tinyobjloader's own triangulation of faces
// with more than four vertices reads vertex data without bounds checks, so a face with a bad index
// could crash it. Faces are therefore read untriangulated and split with PolygonTriangulator,
// the same ear clipping NFF polygons use.
#include "parse/ObjLoader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <istream>
#include <regex>
#include <sstream>
#include <streambuf>
#include <string_view>
#include <unordered_map>

#include "parse/PolygonTriangulator.h"
#include "parse/PrintableText.h"
#include "scene/MeshBudget.h"
#include "util/HugePages.h"

namespace prism {

namespace {

std::string readObjFile(const std::string& path, const FileLoc& referencedFrom,
                        const MemoryLimit& limit) {
  auto fail = [&](int error) {
    throw SceneError(referencedFrom,
                     "cannot open mesh file '" + path + "': " + std::strerror(error));
  };
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(EISDIR);
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > limit.bytes) {
    throw SceneError(referencedFrom, memoryRefusal("reading mesh file '" + path + "'", size, limit,
                                                   "simplify the mesh or raise --memory-limit"));
  }
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) fail(errno);
  std::string text;
  // One allocation of the file's size, read into directly: growing the string by appending
  // copied a 75 MB file about twice over and faulted in every copy (0.86 s of a 2 M-triangle
  // parse). What the size did not cover (a pipe reports none) is appended in chunks below.
  if (!ec && size > 0) {
    text.reserve(size);
    preferHugePages(text.data(), size);
    text.resize(size);
    text.resize(std::fread(text.data(), 1, size, file));
  }
  char buffer[1 << 16];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, file)) > 0) text.append(buffer, n);
  const bool failed = std::ferror(file);
  const int error = errno;
  std::fclose(file);
  if (failed) fail(error);
  return text;
}

// A read-only stream buffer over text that stays where it is.
class TextInPlace : public std::streambuf {
 public:
  explicit TextInPlace(const std::string& text) {
    // The get area only: nothing is ever written through these pointers.
    char* begin = const_cast<char*>(text.data());
    setg(begin, begin, begin + text.size());
  }
};

// Where the vertex and face statements are, so errors found after tinyobjloader has read the file
// can name a line. tinyobjloader keeps them in file order and drops nothing that passes the checks
// here, so the k-th face it reports is the k-th 'f' line.
struct ObjLines {
  std::vector<int> vertexLines;  // line of each 'v' statement
  std::vector<int> faceLines;    // line of each 'f' statement
  size_t normals = 0;            // 'vn' statements
  size_t corners = 0;            // face corners, over all faces
  size_t triangles = 0;          // after triangulation
};

struct Word {
  std::string_view text;
  int column = 0;
};

bool isBlank(char c) {
  return c == ' ' || c == '\t';
}

// Into `words`, reused from line to line (an allocation per line was a third of the scan).
// Plain loops: find_first_of with a set of characters calls memchr once per character.
void splitWords(std::string_view line, std::vector<Word>& words) {
  words.clear();
  const size_t n = line.size();
  size_t i = 0;
  for (;;) {
    while (i < n && isBlank(line[i])) ++i;
    if (i == n || line[i] == '#') break;
    const size_t begin = i;
    while (i < n && !isBlank(line[i])) ++i;
    words.push_back({line.substr(begin, i - begin), static_cast<int>(begin) + 1});
  }
}

// The next position at or after `from` of one character, found with memchr and remembered, so
// the text is searched once for it however many lines ask.
class NextOf {
 public:
  NextOf(const std::string& text, char c) : text_(text), c_(c) {}
  size_t from(size_t position) {
    if (!known_ || at_ < position) {
      const void* found = std::memchr(text_.data() + position, c_, text_.size() - position);
      at_ = found ? static_cast<size_t>(static_cast<const char*>(found) - text_.data())
                  : text_.size();
      known_ = true;
    }
    return at_;
  }

 private:
  const std::string& text_;
  char c_;
  size_t at_ = 0;
  bool known_ = false;
};

// tinyobjloader reads a malformed or non-finite coordinate as 0 without a word, so vertex lines
// are checked here first. Faces need three corners; tinyobjloader would drop shorter ones.
ObjLines scanObjLines(const std::string& text, const std::string& path) {
  ObjLines lines;
  int lineNumber = 0;
  size_t start = 0;
  std::vector<Word> words;
  NextOf newline(text, '\n'), carriageReturn(text, '\r');
  while (start < text.size()) {
    // Lines end in \n, \r\n or a lone \r, as tinyobjloader counts them.
    const size_t end = std::min(newline.from(start), carriageReturn.from(start));
    ++lineNumber;
    splitWords(std::string_view(text).substr(start, end - start), words);
    start = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
    if (words.empty()) continue;
    auto loc = [&](const Word& word) { return FileLoc{path, lineNumber, word.column}; };
    if (words[0].text == "v") {
      lines.vertexLines.push_back(lineNumber);
      if (words.size() < 4) throw SceneError(loc(words[0]), "vertex needs 3 coordinates");
      for (size_t k = 1; k < words.size(); ++k) {
        const std::string_view w = words[k].text;
        double value = 0.0;
        const char* first = w.data() + (w.starts_with('+') ? 1 : 0);
        const auto [ptr, ec] = std::from_chars(first, w.data() + w.size(), value);
        if (ec == std::errc::result_out_of_range ||
            (ec == std::errc() && ptr == w.data() + w.size() &&
             !std::isfinite(static_cast<float>(value)))) {
          throw SceneError(loc(words[k]), "non-finite coordinate '" + printableExcerpt(w) + "'");
        }
        if (ec != std::errc() || ptr != w.data() + w.size()) {
          throw SceneError(loc(words[k]),
                           "expected a number but found '" + printableExcerpt(w) + "'");
        }
      }
    } else if (words[0].text == "f") {
      lines.faceLines.push_back(lineNumber);
      if (words.size() < 4) throw SceneError(loc(words[0]), "face needs at least 3 vertices");
      lines.corners += words.size() - 1;
      lines.triangles += words.size() - 3;
    } else if (words[0].text == "vn") {
      ++lines.normals;
    }
  }
  return lines;
}

FileLoc lineLoc(const std::string& path, const std::vector<int>& lines, size_t index) {
  return FileLoc{path, index < lines.size() ? lines[index] : 0, 1};
}

// tinyobjloader's messages end in "line N.)" where it knows the line.
FileLoc locFromMessage(const std::string& path, const std::string& message) {
  static const std::regex linePattern("line:? ([0-9]+)");
  std::smatch match;
  if (std::regex_search(message, match, linePattern)) {
    return FileLoc{path, std::stoi(match[1].str()), 1};
  }
  return FileLoc{path, 0, 0};
}

std::string firstLine(std::string message) {
  message = message.substr(0, message.find('\n'));
  while (!message.empty() && (message.back() == '.' || message.back() == ' ')) message.pop_back();
  return message;
}

// Warnings that mean the geometry read is not what the file says (as opposed to, say, a missing
// .mtl file, which does not matter because the scene assigns the material).
bool isBadDataWarning(const std::string& warning) {
  return warning.find("out of bounds") != std::string::npos ||
         warning.find("Degenerated face") != std::string::npos ||
         warning.find("invalid") != std::string::npos;
}

}  // namespace

MeshDesc loadObjMesh(const std::string& path, const FileLoc& referencedFrom,
                     const MemoryLimit& limit) {
  return parseObjMesh(readObjFile(path, referencedFrom, limit), path, referencedFrom, limit);
}

MeshDesc parseObjMesh(const std::string& text, const std::string& path,
                      const FileLoc& referencedFrom, const MemoryLimit& limit) {
  const ObjLines lines = scanObjLines(text, path);
  const FileLoc fileLoc{path, 0, 0};
  const size_t positions = lines.vertexLines.size();
  const uint64_t needed =
      saturatingAdd(objReadBytes(text.size(), positions, lines.normals, lines.corners,
                                 lines.faceLines.size(), lines.triangles),
                    meshBuildBytes(lines.triangles, positions));
  if (needed > limit.bytes) {
    throw SceneError(
        referencedFrom.file.empty() ? fileLoc : referencedFrom,
        memoryRefusal("mesh file '" + path + "' (" + std::to_string(lines.triangles) +
                          " triangles, " + std::to_string(positions) + " vertices) read and built",
                      needed, limit, "simplify the mesh or raise --memory-limit"));
  }

  // Read in place (ObjReader::ParseFromString copies the text into a string buffer first), with
  // no material library: the scene assigns the material, so a missing .mtl is no error.
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  TextInPlace objText(text);
  std::istream objStream(&objText);
  std::istringstream noMaterialText;
  tinyobj::MaterialStreamReader noMaterials(noMaterialText);
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &objStream, &noMaterials,
                        /*triangulate=*/false, /*default_vcols_fallback=*/false) ||
      !error.empty()) {
    throw SceneError(locFromMessage(path, error),
                     "invalid OBJ data: " + (error.empty() ? "unreadable" : firstLine(error)));
  }

  const size_t vertexCount = attrib.vertices.size() / 3;
  const size_t normalCount = attrib.normals.size() / 3;
  for (size_t i = 0; i < vertexCount; ++i) {
    for (int k = 0; k < 3; ++k) {
      // Checked as text above; this catches what tinyobjloader's own number parser overflows.
      if (!std::isfinite(static_cast<float>(attrib.vertices[3 * i + k]))) {
        throw SceneError(lineLoc(path, lines.vertexLines, i),
                         "vertex " + std::to_string(i + 1) + " has a non-finite coordinate");
      }
    }
  }
  auto position = [&](int i) {
    return Vec3(attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]);
  };
  auto normal = [&](int i) {
    return Vec3(attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]);
  };

  // First pass: check every face's indices and decide whether the mesh keeps vertex normals.
  bool smooth = true;
  size_t face = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    size_t first = 0;
    for (unsigned char corners : mesh.num_face_vertices) {
      // Made only for a message: a FileLoc copies the path, once per face otherwise.
      const auto loc = [&] { return lineLoc(path, lines.faceLines, face); };
      if (corners < 3 || first + corners > mesh.indices.size()) {
        // tinyobjloader counts a face's vertices in a byte.
        throw SceneError(loc(), "face has fewer than 3 or more than 255 vertices");
      }
      for (size_t k = first; k < first + corners; ++k) {
        const tinyobj::index_t& index = mesh.indices[k];
        if (index.vertex_index < 0 || static_cast<size_t>(index.vertex_index) >= vertexCount) {
          throw SceneError(loc(), "face refers to vertex " +
                                      std::to_string(index.vertex_index + 1) +
                                      " but the file has " + std::to_string(vertexCount));
        }
        if (index.normal_index < 0) {
          smooth = false;  // a face without normals: the whole mesh is shaded flat
        } else if (static_cast<size_t>(index.normal_index) >= normalCount) {
          throw SceneError(loc(), "face refers to normal " +
                                      std::to_string(index.normal_index + 1) +
                                      " but the file has " + std::to_string(normalCount));
        } else {
          const Vec3 n = normal(index.normal_index);
          if (!isFinite(n)) throw SceneError(loc(), "face uses a non-finite normal");
          // A zero normal cannot be interpolated; exporters write them for degenerate faces.
          if (maxAbsComponent(n) == 0.0f) smooth = false;
        }
      }
      first += corners;
      ++face;
    }
    if (first != mesh.indices.size()) {
      throw SceneError(fileLoc, "a face has more than 255 vertices");
    }
  }
  if (!warning.empty() && isBadDataWarning(warning)) {
    throw SceneError(locFromMessage(path, warning), "invalid OBJ data: " + firstLine(warning));
  }

  // Second pass: one output vertex per distinct (position, normal) pair, so normals can be
  // indexed like positions.
  MeshDesc result;
  result.source = path;
  result.loc = referencedFrom;
  std::unordered_map<uint64_t, uint32_t> vertexOf;
  vertexOf.reserve(vertexCount);
  result.positions.reserve(vertexCount);
  if (smooth) result.normals.reserve(vertexCount);
  reserveOnHugePages(result.indices, 3 * lines.triangles);
  auto outputVertex = [&](const tinyobj::index_t& index) {
    const uint32_t normalKey = smooth ? static_cast<uint32_t>(index.normal_index) : 0xffffffffu;
    const uint64_t key = (uint64_t(uint32_t(index.vertex_index)) << 32) | normalKey;
    auto [it, inserted] = vertexOf.try_emplace(key, static_cast<uint32_t>(result.positions.size()));
    if (inserted) {
      result.positions.push_back(position(index.vertex_index));
      if (smooth) result.normals.push_back(glm::normalize(normal(index.normal_index)));
    }
    return it->second;
  };
  std::vector<Vec3> polygon;
  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    size_t first = 0;
    for (unsigned char corners : mesh.num_face_vertices) {
      const tinyobj::index_t* corner = &mesh.indices[first];
      first += corners;
      if (corners == 3) {
        for (int k = 0; k < 3; ++k) result.indices.push_back(outputVertex(corner[k]));
        continue;
      }
      polygon.clear();
      for (int k = 0; k < corners; ++k) polygon.push_back(position(corner[k].vertex_index));
      for (uint32_t local : triangulatePolygon(polygon)) {
        result.indices.push_back(outputVertex(corner[local]));
      }
    }
  }
  if (result.indices.empty()) throw SceneError(fileLoc, "mesh file has no triangles");
  return result;
}

}  // namespace prism

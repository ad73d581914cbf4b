// The header of a PLY file (Greg Turk's polygon format, as Stanford's scans and most mesh tools
// write it): which elements follow, how many of each, and the properties of each, in order.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace prism {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

// Bytes of one value of the type in a binary body.
int plyTypeBytes(PlyType type);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // of the value, or of each list item
  bool isList = false;
  PlyType countType = PlyType::UInt8;  // of a list's length
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
  int line = 0;  // of its 'element' statement

  // Index of the property of that name, or -1.
  int find(std::string_view property) const;
  // The fewest bytes one element takes in the body (every list empty; in ASCII at least a
  // character and a separator per value): what refuses counts the file cannot hold.
  uint64_t minimumBytes(PlyFormat format) const;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  size_t bodyOffset = 0;  // the first byte after "end_header" and its line end
  int bodyLine = 0;       // the line the body starts on (for ASCII errors)

  const PlyElement* find(std::string_view element) const;
};

// Reads the header at the start of bytes. Throws SceneError at path:line:col where it is
// malformed, and where an element declares more than the rest of the file can hold.
PlyHeader parsePlyHeader(std::string_view bytes, const std::string& path);

// Whether bytes start like a PLY file ("ply" alone on the first line).
bool looksLikePly(std::string_view bytes);

}  // namespace prism

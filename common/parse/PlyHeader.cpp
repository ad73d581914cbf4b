#include "parse/PlyHeader.h"

#include <charconv>

#include "parse/PrintableText.h"
#include "util/FileLoc.h"

namespace prism {

namespace {

struct Word {
  std::string_view text;
  int column = 0;
};

std::vector<Word> wordsOf(std::string_view line) {
  std::vector<Word> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t begin = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > begin) words.push_back({line.substr(begin, i - begin), static_cast<int>(begin) + 1});
  }
  return words;
}

bool typeNamed(std::string_view name, PlyType& type) {
  static const struct {
    const char* name;
    PlyType type;
  } kNames[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& entry : kNames) {
    if (name == entry.name) {
      type = entry.type;
      return true;
    }
  }
  return false;
}

// Headers are short; one longer than this is not a PLY header.
constexpr size_t kMaxHeaderBytes = size_t{1} << 20;

[[noreturn]] void failAt(const std::string& path, int line, int column,
                         const std::string& message) {
  throw SceneError(FileLoc{path, line, column}, message);
}

// One header line in words, and where it is: what its readers report their errors at.
struct HeaderLine {
  const std::string& path;
  int number;
  std::vector<Word> words;

  [[noreturn]] void fail(int column, const std::string& message) const {
    failAt(path, number, column, message);
  }
  void expectWords(size_t n, const char* form) const {
    if (words.size() != n) fail(words[0].column, std::string("expected '") + form + "'");
  }
};

// "format ascii|binary_little_endian|binary_big_endian 1.0", the only one in the header.
PlyFormat readFormat(const HeaderLine& line, bool& formatSeen) {
  const std::vector<Word>& words = line.words;
  line.expectWords(3, "format ascii|binary_little_endian|binary_big_endian 1.0");
  if (formatSeen) line.fail(words[0].column, "a second 'format' line");
  formatSeen = true;
  const std::string_view name = words[1].text;
  PlyFormat format = PlyFormat::Ascii;
  if (name == "ascii") {
    format = PlyFormat::Ascii;
  } else if (name == "binary_little_endian") {
    format = PlyFormat::BinaryLittleEndian;
  } else if (name == "binary_big_endian") {
    format = PlyFormat::BinaryBigEndian;
  } else {
    line.fail(words[1].column, "unknown format '" + printableExcerpt(name) +
                                   "' (ascii, binary_little_endian or binary_big_endian)");
  }
  if (words[2].text != "1.0") {
    line.fail(words[2].column,
              "unknown version '" + printableExcerpt(words[2].text) + "' (only 1.0 exists)");
  }
  return format;
}

// "element NAME COUNT".
PlyElement readElement(const HeaderLine& line) {
  const std::vector<Word>& words = line.words;
  line.expectWords(3, "element NAME COUNT");
  PlyElement element;
  element.name = std::string(words[1].text);
  element.line = line.number;
  const std::string_view count = words[2].text;
  const auto [ptr, ec] = std::from_chars(count.data(), count.data() + count.size(), element.count);
  if (ec != std::errc() || ptr != count.data() + count.size()) {
    line.fail(words[2].column,
              "expected an element count but found '" + printableExcerpt(count) + "'");
  }
  return element;
}

// "property TYPE NAME" or "property list COUNT_TYPE ITEM_TYPE NAME".
PlyProperty readProperty(const HeaderLine& line) {
  const std::vector<Word>& words = line.words;
  PlyProperty property;
  size_t nameAt = 2;
  if (words.size() >= 2 && words[1].text == "list") {
    line.expectWords(5, "property list COUNT_TYPE ITEM_TYPE NAME");
    property.isList = true;
    if (!typeNamed(words[2].text, property.countType) || property.countType == PlyType::Float32 ||
        property.countType == PlyType::Float64) {
      line.fail(words[2].column, "expected an integer type for a list's length but found '" +
                                     printableExcerpt(words[2].text) + "'");
    }
    if (!typeNamed(words[3].text, property.type)) {
      line.fail(words[3].column, "unknown type '" + printableExcerpt(words[3].text) + "'");
    }
    nameAt = 4;
  } else {
    line.expectWords(3, "property TYPE NAME");
    if (!typeNamed(words[1].text, property.type)) {
      line.fail(words[1].column, "unknown type '" + printableExcerpt(words[1].text) + "'");
    }
  }
  property.name = std::string(words[nameAt].text);
  return property;
}

// Refuses counts the body cannot hold, before anything is allocated for them.
void checkCountsFitBody(const PlyHeader& header, uint64_t body, const std::string& path) {
  uint64_t minimum = 0;
  // An ASCII body's last value may lack the separator the minimum counts for it.
  const uint64_t available = body + (header.format == PlyFormat::Ascii ? 1 : 0);
  for (const PlyElement& element : header.elements) {
    const uint64_t each = element.minimumBytes(header.format);
    const bool tooMany = each == 0
                             ? element.count > 0
                             : element.count > (available - std::min(minimum, available)) / each;
    if (tooMany) {
      failAt(path, element.line, 1,
             "element '" + printableExcerpt(element.name) + "' declares " +
                 std::to_string(element.count) + " but the " + std::to_string(body) +
                 "-byte body cannot hold that many");
    }
    minimum += element.count * each;
  }
}

}  // namespace

int plyTypeBytes(PlyType type) {
  switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 1;
}

int PlyElement::find(std::string_view property) const {
  for (size_t i = 0; i < properties.size(); ++i) {
    if (properties[i].name == property) return static_cast<int>(i);
  }
  return -1;
}

uint64_t PlyElement::minimumBytes(PlyFormat format) const {
  uint64_t bytes = 0;
  for (const PlyProperty& property : properties) {
    if (format == PlyFormat::Ascii) {
      bytes += 2;
    } else {
      bytes +=
          static_cast<uint64_t>(plyTypeBytes(property.isList ? property.countType : property.type));
    }
  }
  return bytes;
}

const PlyElement* PlyHeader::find(std::string_view element) const {
  for (const PlyElement& e : elements) {
    if (e.name == element) return &e;
  }
  return nullptr;
}

bool looksLikePly(std::string_view bytes) {
  return bytes.starts_with("ply\n") || bytes.starts_with("ply\r\n") || bytes.starts_with("ply\r");
}

PlyHeader parsePlyHeader(std::string_view bytes, const std::string& path) {
  PlyHeader header;
  int line = 0;
  size_t start = 0;
  bool formatSeen = false;
  if (!looksLikePly(bytes)) failAt(path, 1, 1, "not a PLY file: it must start with a line 'ply'");
  for (;;) {
    if (start >= bytes.size() || start > kMaxHeaderBytes) {
      failAt(path, line + 1, 1, "the header has no 'end_header' line");
    }
    size_t end = bytes.find_first_of("\r\n", start);
    if (end == std::string_view::npos) end = bytes.size();
    const std::string_view text = bytes.substr(start, end - start);
    start = end + (bytes.compare(end, 2, "\r\n") == 0 ? 2 : 1);
    ++line;
    const HeaderLine current{path, line, wordsOf(text)};
    if (line == 1 || current.words.empty()) continue;  // "ply"
    const std::string_view keyword = current.words[0].text;
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      current.expectWords(1, "end_header");
      break;
    }
    if (keyword == "format") {
      header.format = readFormat(current, formatSeen);
    } else if (keyword == "element") {
      header.elements.push_back(readElement(current));
    } else if (keyword == "property") {
      if (header.elements.empty()) {
        current.fail(current.words[0].column, "a property before any element");
      }
      header.elements.back().properties.push_back(readProperty(current));
    } else {
      current.fail(current.words[0].column,
                   "unknown header line '" + printableExcerpt(keyword) + "'");
    }
  }
  if (!formatSeen) failAt(path, line, 1, "the header has no 'format' line");
  header.bodyOffset = std::min(start, bytes.size());
  header.bodyLine = line + 1;
  checkCountsFitBody(header, bytes.size() - header.bodyOffset, path);
  return header;
}

}  // namespace prism

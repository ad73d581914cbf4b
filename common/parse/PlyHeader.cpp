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
  auto fail = [&](int column, const std::string& message) -> void {
    throw SceneError(FileLoc{path, line, column}, message);
  };
  if (!looksLikePly(bytes)) {
    line = 1;
    fail(1, "not a PLY file: it must start with a line 'ply'");
  }
  for (;;) {
    if (start >= bytes.size() || start > kMaxHeaderBytes) {
      ++line;
      fail(1, "the header has no 'end_header' line");
    }
    size_t end = bytes.find_first_of("\r\n", start);
    if (end == std::string_view::npos) end = bytes.size();
    const std::string_view text = bytes.substr(start, end - start);
    start = end + (bytes.compare(end, 2, "\r\n") == 0 ? 2 : 1);
    ++line;
    const std::vector<Word> words = wordsOf(text);
    if (line == 1 || words.empty()) continue;  // "ply"
    const std::string_view keyword = words[0].text;
    auto expectWords = [&](size_t n, const char* form) {
      if (words.size() != n) fail(words[0].column, std::string("expected '") + form + "'");
    };
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      expectWords(1, "end_header");
      break;
    }
    if (keyword == "format") {
      expectWords(3, "format ascii|binary_little_endian|binary_big_endian 1.0");
      if (formatSeen) fail(words[0].column, "a second 'format' line");
      formatSeen = true;
      const std::string_view name = words[1].text;
      if (name == "ascii") {
        header.format = PlyFormat::Ascii;
      } else if (name == "binary_little_endian") {
        header.format = PlyFormat::BinaryLittleEndian;
      } else if (name == "binary_big_endian") {
        header.format = PlyFormat::BinaryBigEndian;
      } else {
        fail(words[1].column, "unknown format '" + printableExcerpt(name) +
                                  "' (ascii, binary_little_endian or binary_big_endian)");
      }
      if (words[2].text != "1.0") {
        fail(words[2].column,
             "unknown version '" + printableExcerpt(words[2].text) + "' (only 1.0 exists)");
      }
    } else if (keyword == "element") {
      expectWords(3, "element NAME COUNT");
      PlyElement element;
      element.name = std::string(words[1].text);
      element.line = line;
      const std::string_view count = words[2].text;
      const auto [ptr, ec] =
          std::from_chars(count.data(), count.data() + count.size(), element.count);
      if (ec != std::errc() || ptr != count.data() + count.size()) {
        fail(words[2].column,
             "expected an element count but found '" + printableExcerpt(count) + "'");
      }
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) fail(words[0].column, "a property before any element");
      PlyProperty property;
      size_t nameAt = 2;
      if (words.size() >= 2 && words[1].text == "list") {
        expectWords(5, "property list COUNT_TYPE ITEM_TYPE NAME");
        property.isList = true;
        if (!typeNamed(words[2].text, property.countType) ||
            property.countType == PlyType::Float32 || property.countType == PlyType::Float64) {
          fail(words[2].column, "expected an integer type for a list's length but found '" +
                                    printableExcerpt(words[2].text) + "'");
        }
        if (!typeNamed(words[3].text, property.type)) {
          fail(words[3].column, "unknown type '" + printableExcerpt(words[3].text) + "'");
        }
        nameAt = 4;
      } else {
        expectWords(3, "property TYPE NAME");
        if (!typeNamed(words[1].text, property.type)) {
          fail(words[1].column, "unknown type '" + printableExcerpt(words[1].text) + "'");
        }
      }
      property.name = std::string(words[nameAt].text);
      header.elements.back().properties.push_back(std::move(property));
    } else {
      fail(words[0].column, "unknown header line '" + printableExcerpt(keyword) + "'");
    }
  }
  if (!formatSeen) fail(1, "the header has no 'format' line");
  header.bodyOffset = std::min(start, bytes.size());
  header.bodyLine = line + 1;

  // Counts the body cannot hold are refused here, before anything is allocated for them.
  uint64_t minimum = 0;
  const uint64_t body = bytes.size() - header.bodyOffset;
  // An ASCII body's last value may lack the separator the minimum counts for it.
  const uint64_t available = body + (header.format == PlyFormat::Ascii ? 1 : 0);
  for (const PlyElement& element : header.elements) {
    const uint64_t each = element.minimumBytes(header.format);
    const bool tooMany = each == 0
                             ? element.count > 0
                             : element.count > (available - std::min(minimum, available)) / each;
    if (tooMany) {
      line = element.line;
      fail(1, "element '" + printableExcerpt(element.name) + "' declares " +
                  std::to_string(element.count) + " but the " + std::to_string(body) +
                  "-byte body cannot hold that many");
    }
    minimum += element.count * each;
  }
  return header;
}

}  // namespace prism

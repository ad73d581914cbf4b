#include "parse/GltfGlb.h"

#include <cstring>

#include "util/FileLoc.h"

namespace prism {

namespace {

constexpr uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr uint32_t kBinChunk = 0x004E4942;   // "BIN\0"

uint32_t readU32(std::string_view bytes, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, 4);  // GLB is little-endian, as every supported host is
  return v;
}

[[noreturn]] void failAt(const std::string& file, size_t byte, const std::string& message) {
  throw SceneError(FileLoc{file, 0, 0}, "byte " + std::to_string(byte) + ": " + message);
}

struct Chunk {
  uint32_t type = 0;
  size_t offset = 0;  // of its data
  size_t length = 0;
};

Chunk readChunk(std::string_view bytes, size_t at, size_t end, const std::string& file) {
  if (at > end || end - at < 8)
    failAt(file, at, "the chunk header is cut off (the file is truncated)");
  Chunk chunk{readU32(bytes, at + 4), at + 8, readU32(bytes, at)};
  if (chunk.length > end - chunk.offset) {
    failAt(file, at,
           "the chunk says it holds " + std::to_string(chunk.length) + " bytes, but only " +
               std::to_string(end - chunk.offset) + " follow (the file is truncated)");
  }
  return chunk;
}

}  // namespace

bool looksLikeGlb(std::string_view bytes) {
  return bytes.size() >= 4 && readU32(bytes, 0) == kMagic;
}

GlbChunks splitGlb(std::string_view bytes, const std::string& file) {
  if (bytes.size() < 12) failAt(file, 0, "too short for a binary glTF header (12 bytes)");
  if (!looksLikeGlb(bytes)) failAt(file, 0, "not a binary glTF file (no \"glTF\" magic)");
  const uint32_t version = readU32(bytes, 4);
  if (version != 2) {
    failAt(file, 4,
           "binary glTF version " + std::to_string(version) + " is not read (only version 2)");
  }
  const uint32_t length = readU32(bytes, 8);
  if (length > bytes.size()) {
    failAt(file, 8,
           "the header says the file has " + std::to_string(length) + " bytes, but it has " +
               std::to_string(bytes.size()) + " (the file is truncated)");
  }
  if (length < 20) {
    failAt(file, 8,
           "the header says the file has " + std::to_string(length) +
               " bytes, too few for a header and a chunk");
  }
  const size_t end = length;  // bytes past the stated length are ignored
  const Chunk json = readChunk(bytes, 12, end, file);
  if (json.type != kJsonChunk) failAt(file, 16, "the first chunk is not the JSON chunk");
  GlbChunks chunks;
  chunks.json = bytes.substr(json.offset, json.length);
  size_t at = json.offset + json.length;
  at += (4 - at % 4) % 4;  // chunks are 4-byte aligned
  if (at + 8 <= end) {
    const Chunk bin = readChunk(bytes, at, end, file);
    if (bin.type == kBinChunk) {
      chunks.hasBin = true;
      chunks.bin = {reinterpret_cast<const uint8_t*>(bytes.data()) + bin.offset, bin.length};
    }
  }
  return chunks;
}

}  // namespace prism

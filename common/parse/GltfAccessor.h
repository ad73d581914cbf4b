// glTF accessors: typed views of a buffer (component type, element type, count, byte stride,
// normalized integers, sparse substitutions), checked against their buffer view and buffer
// before a byte is read, and read into Prism's floats and indices.
#pragma once

#include <cstdint>
#include <string>

#include "parse/GltfDocument.h"

namespace prism {

struct GltfAccessor {
  std::string file;
  std::string path;            // "accessors[3]"
  uint32_t componentType = 0;  // 5120 (i8) ... 5126 (f32)
  int components = 1;          // SCALAR 1, VEC2 2, VEC3 3, VEC4 4 (matrices are refused)
  bool normalized = false;
  uint64_t count = 0;
  const uint8_t* data = nullptr;  // nullptr: no buffer view, every element zero
  uint64_t stride = 0;
  // Sparse substitutions: `sparseCount` indices (u8/u16/u32) and values (the accessor's type,
  // tightly packed).
  uint64_t sparseCount = 0;
  const uint8_t* sparseIndices = nullptr;
  uint32_t sparseIndexType = 0;
  const uint8_t* sparseValues = nullptr;
};

// The accessor at index, checked: its type, and that its elements (and sparse arrays) lie inside
// their buffer views and buffers. `from` is the JSON value that names it (errors point there).
GltfAccessor viewAccessor(const GltfDocument& doc, uint64_t index, const GltfJson& from);

// Reads count × components floats into out (components may be fewer than the accessor's: the
// first ones are read). Integer components become floats: normalized ones scaled to [0, 1] or
// [-1, 1] as the glTF specification says, others as they are (KHR_mesh_quantization).
void readFloats(const GltfAccessor& accessor, int components, float* out);

// Reads a SCALAR unsigned-integer accessor (u8, u16, u32) into out (count values); returns the
// largest value read, or more (sparse substitutions are counted without their replaced value).
uint32_t readIndices(const GltfAccessor& accessor, uint32_t* out);

// Bytes of one component of the type (0 for an unknown type).
int componentBytes(uint32_t componentType);

}  // namespace prism

#include "parse/GltfAccessor.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <limits>
#include <type_traits>

#include "util/Parallel.h"

namespace prism {

namespace {

constexpr uint64_t kBlock = 1 << 16;  // elements a thread reads at a time
constexpr uint32_t kI8 = 5120, kU8 = 5121, kI16 = 5122, kU16 = 5123, kU32 = 5125, kF32 = 5126;

int componentsOf(const GltfJson& type) {
  const std::string_view t = type.string();
  if (t == "SCALAR") return 1;
  if (t == "VEC2") return 2;
  if (t == "VEC3") return 3;
  if (t == "VEC4") return 4;
  if (t == "MAT2" || t == "MAT3" || t == "MAT4") type.fail("matrix accessors are not read here");
  type.fail("unknown accessor type '" + std::string(t) + "'");
}

// The bytes [offset, offset + length) of the buffer view, checked against its buffer.
struct ViewBytes {
  const uint8_t* data;
  uint64_t length;
  uint64_t stride;  // 0: tightly packed
};

ViewBytes bufferViewBytes(const GltfDocument& doc, uint64_t index, const GltfJson& from) {
  const GltfJson& view = doc.at(doc.bufferViews, index, from, "bufferViews");
  const GltfJson buffer = view.required("buffer");
  const uint64_t b = buffer.index();
  doc.at(doc.buffers, b, buffer, "buffers");
  const uint64_t offset = view.indexOr("byteOffset", 0);
  const uint64_t length = view.required("byteLength").index();
  const uint64_t size = doc.bufferBytes[b].size();
  if (offset > size || length > size - offset) {
    view.fail("bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) +
              " lie past the end of buffers[" + std::to_string(b) + "] (" + std::to_string(size) +
              " bytes)");
  }
  const uint64_t stride = view.indexOr("byteStride", 0);
  if (stride != 0 && (stride < 4 || stride > 252)) {
    view.required("byteStride").fail("a byte stride must be between 4 and 252");
  }
  return {doc.bufferBytes[b].data() + offset, length, stride};
}

// Checks that `count` elements of `elementBytes`, `stride` apart, from byteOffset fit the view.
void checkFits(const GltfJson& at, const ViewBytes& view, uint64_t offset, uint64_t count,
               uint64_t stride, uint64_t elementBytes) {
  const uint64_t needed =
      count == 0 ? 0 : saturatingAdd(saturatingMultiply(count - 1, stride), elementBytes);
  if (offset > view.length || needed > view.length - offset) {
    at.fail(std::to_string(count) + " elements from byte " + std::to_string(offset) + " need " +
            std::to_string(saturatingAdd(offset, needed)) + " bytes, but the buffer view has " +
            std::to_string(view.length));
  }
}

void readSparse(const GltfDocument& doc, const GltfJson& sparse, GltfAccessor& a) {
  a.sparseCount = sparse.required("count").index();
  if (a.sparseCount == 0) sparse.required("count").fail("a sparse accessor needs 1 or more values");
  const GltfJson indices = sparse.required("indices");
  a.sparseIndexType = static_cast<uint32_t>(indices.required("componentType").index());
  if (a.sparseIndexType != kU8 && a.sparseIndexType != kU16 && a.sparseIndexType != kU32) {
    indices.required("componentType").fail("sparse indices must be unsigned integers");
  }
  const GltfJson indexView = indices.required("bufferView");
  const ViewBytes iv = bufferViewBytes(doc, indexView.index(), indexView);
  const uint64_t ioffset = indices.indexOr("byteOffset", 0);
  const int ib = componentBytes(a.sparseIndexType);
  checkFits(indices, iv, ioffset, a.sparseCount, ib, ib);
  a.sparseIndices = iv.data + ioffset;
  const GltfJson values = sparse.required("values");
  const GltfJson valueView = values.required("bufferView");
  const ViewBytes vv = bufferViewBytes(doc, valueView.index(), valueView);
  const uint64_t voffset = values.indexOr("byteOffset", 0);
  const uint64_t element = uint64_t(componentBytes(a.componentType)) * a.components;
  checkFits(values, vv, voffset, a.sparseCount, element, element);
  a.sparseValues = vv.data + voffset;
}

template <class T>
T load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

template <class T>
float toFloat(const uint8_t* p, bool normalized) {
  const T v = load<T>(p);
  if constexpr (std::is_same_v<T, float>) {
    return v;
  } else {
    if (!normalized) return static_cast<float>(v);
    constexpr float kMax = static_cast<float>(std::numeric_limits<T>::max());
    return std::max(static_cast<float>(v) / kMax, -1.0f);
  }
}

// Elements [begin, end) of the accessor's buffer view.
template <class T>
void readDense(const GltfAccessor& a, int components, float* out, uint64_t begin, uint64_t end) {
  const uint64_t stride = a.stride;
  if (std::is_same_v<T, float> && components == a.components && stride == 4u * components) {
    // The common case, packed floats.
    std::memcpy(out + begin * components, a.data + begin * stride, (end - begin) * stride);
    return;
  }
  for (uint64_t i = begin; i < end; ++i) {
    const uint8_t* p = a.data + i * stride;
    for (int c = 0; c < components; ++c) {
      out[i * components + c] = toFloat<T>(p + c * sizeof(T), a.normalized);
    }
  }
}

// The element the k-th sparse value replaces (indices of ib bytes), checked against the count.
uint64_t sparseIndex(const GltfAccessor& a, int ib, uint64_t k) {
  const uint8_t* ip = a.sparseIndices + k * ib;
  const uint64_t i = ib == 1 ? *ip : ib == 2 ? load<uint16_t>(ip) : load<uint32_t>(ip);
  if (i >= a.count) {
    throw SceneError(FileLoc{a.file, 0, 0}, a.path + ".sparse: index " + std::to_string(i) +
                                                " is past the accessor's " +
                                                std::to_string(a.count) + " elements");
  }
  return i;
}

template <class T>
void readSparseValues(const GltfAccessor& a, int components, float* out) {
  const int ib = componentBytes(a.sparseIndexType);
  const uint64_t element = sizeof(T) * a.components;
  for (uint64_t k = 0; k < a.sparseCount; ++k) {
    const uint64_t i = sparseIndex(a, ib, k);
    const uint8_t* vp = a.sparseValues + k * element;
    for (int c = 0; c < components; ++c)
      out[i * components + c] = toFloat<T>(vp + c * sizeof(T), a.normalized);
  }
}

template <class T>
void readTyped(const GltfAccessor& a, int components, float* out) {
  // In blocks on every core: the copies fault their pages in together, which is most of the cost.
  forChunks(a.count, kBlock, 0, [&](uint64_t begin, uint64_t end) {
    if (a.data) {
      readDense<T>(a, components, out, begin, end);
    } else {
      std::fill(out + begin * components, out + end * components, 0.0f);
    }
  });
  if (a.sparseCount > 0) readSparseValues<T>(a, components, out);
}

}  // namespace

int componentBytes(uint32_t componentType) {
  switch (componentType) {
    case kI8:
    case kU8:
      return 1;
    case kI16:
    case kU16:
      return 2;
    case kU32:
    case kF32:
      return 4;
    default:
      return 0;
  }
}

GltfAccessor viewAccessor(const GltfDocument& doc, uint64_t index, const GltfJson& from) {
  const GltfJson& json = doc.at(doc.accessors, index, from, "accessors");
  GltfAccessor a;
  a.file = doc.file;
  a.path = json.path();
  const GltfJson type = json.required("componentType");
  a.componentType = static_cast<uint32_t>(type.index());
  if (componentBytes(a.componentType) == 0) {
    type.fail("unknown component type " + std::to_string(type.index()));
  }
  a.components = componentsOf(json.required("type"));
  a.normalized = json.booleanOr("normalized", false);
  a.count = json.required("count").index();
  if (a.count == 0) json.required("count").fail("an accessor needs 1 or more elements");
  const uint64_t element = uint64_t(componentBytes(a.componentType)) * a.components;
  if (const std::optional<uint64_t> view = json.optionalIndex("bufferView")) {
    const ViewBytes bytes = bufferViewBytes(doc, *view, *json.member("bufferView"));
    const uint64_t offset = json.indexOr("byteOffset", 0);
    a.stride = bytes.stride != 0 ? bytes.stride : element;
    if (a.stride < element) {
      json.fail("the buffer view's byte stride (" + std::to_string(a.stride) +
                ") is shorter than an element (" + std::to_string(element) + " bytes)");
    }
    checkFits(json, bytes, offset, a.count, a.stride, element);
    a.data = bytes.data + offset;
  }
  if (const std::optional<GltfJson> sparse = json.member("sparse")) readSparse(doc, *sparse, a);
  return a;
}

void readFloats(const GltfAccessor& a, int components, float* out) {
  components = std::min(components, a.components);
  switch (a.componentType) {
    case kI8:
      readTyped<int8_t>(a, components, out);
      break;
    case kU8:
      readTyped<uint8_t>(a, components, out);
      break;
    case kI16:
      readTyped<int16_t>(a, components, out);
      break;
    case kU16:
      readTyped<uint16_t>(a, components, out);
      break;
    case kU32:
      readTyped<uint32_t>(a, components, out);
      break;
    default:
      readTyped<float>(a, components, out);
      break;
  }
}

uint32_t readIndices(const GltfAccessor& a, uint32_t* out) {
  const int bytes = componentBytes(a.componentType);
  std::atomic<uint32_t> largest{0};
  forChunks(a.count, kBlock, 0, [&](uint64_t begin, uint64_t end) {
    if (bytes == 4 && a.data && a.stride == 4) {
      std::memcpy(out + begin, a.data + begin * 4, (end - begin) * 4);  // packed u32
    } else {
      for (uint64_t i = begin; i < end; ++i) {
        const uint8_t* p = a.data ? a.data + i * a.stride : nullptr;
        out[i] = !p ? 0 : bytes == 1 ? *p : bytes == 2 ? load<uint16_t>(p) : load<uint32_t>(p);
      }
    }
    // The block's largest while it is still in the cache, rather than another pass later.
    const uint32_t blockLargest = *std::max_element(out + begin, out + end);
    uint32_t seen = largest.load();
    while (blockLargest > seen && !largest.compare_exchange_weak(seen, blockLargest)) {
    }
  });
  uint32_t result = largest.load();
  const int ib = componentBytes(a.sparseIndexType);
  for (uint64_t k = 0; k < a.sparseCount; ++k) {
    const uint64_t i = sparseIndex(a, ib, k);
    const uint8_t* vp = a.sparseValues + k * bytes;
    out[i] = bytes == 1 ? *vp : bytes == 2 ? load<uint16_t>(vp) : load<uint32_t>(vp);
    result = std::max(result, out[i]);  // an upper bound: a replaced value may have been largest
  }
  return result;
}

}  // namespace prism

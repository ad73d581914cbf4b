#include "master/remote/ViewProtocol.h"

#include <zstd.h>

#include <cmath>

#include "master/remote/ViewFields.h"
#include "wire/FieldCodec.h"
#include "wire/Messages.h"

namespace prism::wire {
namespace {

constexpr int kMaxSide = 16384;

void checkSide(int32_t side, const char* what) {
  if (side < 1 || side > kMaxSide) {
    throw WireError(std::string("invalid ") + what + " " + std::to_string(side));
  }
}

}  // namespace

void Fields<ViewSettings>::check(const ViewSettings& view) {
  if (view.samplesPerPixel < 1 || view.samplesPerPixel > 65536) {
    throw WireError("invalid samples per pixel " + std::to_string(view.samplesPerPixel));
  }
  if (view.maxPasses < 0 || view.maxPasses > (1 << 20)) {
    throw WireError("invalid pass limit " + std::to_string(view.maxPasses));
  }
  if (!(view.frameTimeSeconds < 3600.0)) {  // NaN too
    throw WireError("invalid frame time " + std::to_string(view.frameTimeSeconds));
  }
  if (view.photonsPerPass > (uint64_t{1} << 32)) {
    throw WireError("invalid photon budget " + std::to_string(view.photonsPerPass));
  }
}

void Fields<ViewerStart>::check(const ViewerStart& start) {
  checkSide(start.width, "frame width");
  checkSide(start.height, "frame height");
  if (!(std::isfinite(start.exposure) && start.exposure > 0.0f)) {
    throw WireError("invalid exposure " + std::to_string(start.exposure));
  }
}

void Fields<FrameScale>::check(const FrameScale& scale) {
  if (scale.numerator < 1 || scale.numerator > 1024 || scale.denominator < 1 ||
      scale.denominator > 1024) {
    throw WireError("invalid frame scale " + std::to_string(scale.numerator) + "/" +
                    std::to_string(scale.denominator));
  }
}

void Fields<LiveStats>::check(const LiveStats& stats) {
  if (stats.ranks.size() > (size_t{1} << 20)) throw WireError("too many ranks in the statistics");
}

void Fields<DisplayNews>::check(const DisplayNews& news) {
  checkSide(news.width, "frame width");
  checkSide(news.height, "frame height");
  if (news.completed.size() > DisplayNews::kMaxCompleted) {
    throw WireError("too many completed passes (" + std::to_string(news.completed.size()) + ")");
  }
  const TileRect& r = news.patch;
  if (r.width == 0 && r.height == 0 && r.x == 0 && r.y == 0) {
    if (!news.patchBytes.empty()) throw WireError("display bytes without a patch");
    return;
  }
  if (r.x < 0 || r.y < 0 || r.width < 1 || r.height < 1 || r.width > news.width - r.x ||
      r.height > news.height - r.y) {
    throw WireError("patch " + std::to_string(r.width) + "x" + std::to_string(r.height) + "+" +
                    std::to_string(r.x) + "+" + std::to_string(r.y) + " outside the " +
                    std::to_string(news.width) + "x" + std::to_string(news.height) + " frame");
  }
  if (news.patchBytes.size() != static_cast<size_t>(r.width) * r.height * 3) {
    throw WireError("patch of " + std::to_string(news.patchBytes.size()) + " bytes, expected " +
                    std::to_string(static_cast<size_t>(r.width) * r.height * 3));
  }
}

}  // namespace prism::wire

namespace prism::view {
namespace {

using wire::WireError;

constexpr int kZstdLevel = 1;  // docs/viewer.md: level 1 keeps a frame's compression near 1 ms

// One compression and one decompression context per thread, kept: making one per message
// allocated (and faulted in) a megabyte of workspace every frame.
struct ZstdContexts {
  ZSTD_CCtx* compress = ZSTD_createCCtx();
  ZSTD_DCtx* decompress = ZSTD_createDCtx();
  ~ZstdContexts() {
    ZSTD_freeCCtx(compress);
    ZSTD_freeDCtx(decompress);
  }
};
ZstdContexts& zstd() {
  thread_local ZstdContexts contexts;
  return contexts;
}

// Compresses raw into packed (its memory kept from message to message).
void compress(const std::vector<uint8_t>& raw, std::vector<uint8_t>& packed) {
  packed.resize(ZSTD_compressBound(raw.size()));
  const size_t size = ZSTD_compressCCtx(zstd().compress, packed.data(), packed.size(), raw.data(),
                                        raw.size(), kZstdLevel);
  if (ZSTD_isError(size)) {
    throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(size));
  }
  packed.resize(size);
}

// Buffers a thread encodes its messages in, kept: a frame's megabytes are written into memory
// already touched instead of fresh pages (on this VM a 6 MB buffer's first touch cost ~15 ms).
struct EncodeScratch {
  std::vector<uint8_t> fields;
  std::vector<uint8_t> packed;
};
EncodeScratch& encodeScratch() {
  thread_local EncodeScratch scratch;
  return scratch;
}

std::vector<uint8_t> decompress(const uint8_t* data, size_t size, size_t maxUnpacked) {
  const unsigned long long declared = ZSTD_getFrameContentSize(data, size);
  if (declared == ZSTD_CONTENTSIZE_ERROR) throw WireError("payload is not a zstd frame");
  if (declared == ZSTD_CONTENTSIZE_UNKNOWN) throw WireError("zstd frame without its size");
  if (declared > maxUnpacked) {
    throw WireError("payload unpacks to " + std::to_string(declared) + " bytes, the limit is " +
                    std::to_string(maxUnpacked));
  }
  std::vector<uint8_t> raw(declared);
  const size_t got = ZSTD_decompressDCtx(zstd().decompress, raw.data(), raw.size(), data, size);
  if (ZSTD_isError(got)) throw WireError(std::string("zstd: ") + ZSTD_getErrorName(got));
  if (got != declared) throw WireError("zstd frame shorter than it says");
  return raw;
}

bool isCompressed(MessageType type) {
  switch (type) {
#define PRISM_VIEW_COMPRESSED(name, number, Type, compressed) \
  case MessageType::name:                                     \
    return compressed;
    PRISM_VIEW_MESSAGES(PRISM_VIEW_COMPRESSED)
#undef PRISM_VIEW_COMPRESSED
  }
  return false;
}

}  // namespace

const char* messageTypeName(MessageType type) {
  switch (type) {
#define PRISM_VIEW_NAME(name, number, Type, compressed) \
  case MessageType::name:                               \
    return #name;
    PRISM_VIEW_MESSAGES(PRISM_VIEW_NAME)
#undef PRISM_VIEW_NAME
  }
  return "unknown";
}

bool isKnownType(uint16_t raw) {
  switch (raw) {
#define PRISM_VIEW_NUMBER(name, number, Type, compressed) case number:
    PRISM_VIEW_MESSAGES(PRISM_VIEW_NUMBER)
#undef PRISM_VIEW_NUMBER
    return true;
  }
  return false;
}

VersionMismatch::VersionMismatch(uint16_t v)
    : WireError("protocol version " + std::to_string(v) + ", this Prism speaks version " +
                std::to_string(kVersion) + ": use the same Prism release on both sides"),
      version(v) {}

Header readHeader(const uint8_t* header, const Limits& limits) {
  wire::ByteReader r(header, kHeaderSize);
  const uint32_t magic = r.readU32();
  if (magic != kMagic) {
    throw WireError("not a Prism viewer message (it does not start with PRSV)");
  }
  const uint16_t version = r.readU16();
  if (version != kVersion) throw VersionMismatch(version);
  const uint16_t type = r.readU16();
  if (!isKnownType(type)) throw WireError("unknown message type " + std::to_string(type));
  Header h{static_cast<MessageType>(type), r.readU64(), r.readU64()};
  if (h.size > limits.maxPayload) {
    throw WireError(std::string(messageTypeName(h.type)) + " of " + std::to_string(h.size) +
                    " bytes, the limit is " + std::to_string(limits.maxPayload));
  }
  return h;
}

Message openPayload(const Header& header, const uint8_t* payload, const Limits& limits) {
  if (wire::fnv1a64(payload, header.size) != header.checksum) {
    throw WireError(std::string(messageTypeName(header.type)) + ": payload checksum mismatch");
  }
  if (isCompressed(header.type)) {
    return {header.type, decompress(payload, header.size, limits.maxUnpacked)};
  }
  return {header.type, std::vector<uint8_t>(payload, payload + header.size)};
}

Message decodeMessage(const uint8_t* data, size_t size, const Limits& limits) {
  if (size < kHeaderSize) {
    throw WireError("message of " + std::to_string(size) + " bytes, a header needs " +
                    std::to_string(kHeaderSize));
  }
  const Header header = readHeader(data, limits);
  if (header.size != size - kHeaderSize) {
    throw WireError("header says " + std::to_string(header.size) + " payload bytes, " +
                    std::to_string(size - kHeaderSize) + " are there");
  }
  return openPayload(header, data + kHeaderSize, limits);
}

namespace {

// The envelope around payload (compressed first where the type is).
std::vector<uint8_t> envelope(MessageType type, const std::vector<uint8_t>& fields) {
  const std::vector<uint8_t>* payload = &fields;
  if (isCompressed(type)) {
    compress(fields, encodeScratch().packed);
    payload = &encodeScratch().packed;
  }
  std::vector<uint8_t> bytes;
  bytes.reserve(kHeaderSize + payload->size());
  wire::ByteWriter w;
  w.reuse(std::move(bytes));
  w.writeU32(kMagic);
  w.writeU16(kVersion);
  w.writeU16(static_cast<uint16_t>(type));
  w.writeU64(payload->size());
  w.writeU64(wire::fnv1a64(payload->data(), payload->size()));
  w.writeRaw(payload->data(), payload->size());
  return w.take();
}

}  // namespace

std::vector<uint8_t> encodePayload(MessageType type, std::vector<uint8_t> fields) {
  return envelope(type, fields);
}

template <ViewMessage T>
std::vector<uint8_t> encode(const T& value) {
  EncodeScratch& scratch = encodeScratch();
  wire::ByteWriter fields;
  fields.reuse(std::move(scratch.fields));
  wire::writeFields(fields, value);
  scratch.fields = fields.take();
  return envelope(MessageTraits<T>::kType, scratch.fields);
}

template <ViewMessage T>
T decode(const Message& message) {
  if (message.type != MessageTraits<T>::kType) {
    throw WireError(std::string("expected ") + messageTypeName(MessageTraits<T>::kType) + ", got " +
                    messageTypeName(message.type));
  }
  T value{};
  wire::ByteReader r(message.payload);
  try {
    wire::readFields(r, value);
    r.expectEnd();
  } catch (const WireError& e) {
    throw WireError(std::string(messageTypeName(message.type)) + ": " + e.what());
  }
  return value;
}

#define PRISM_VIEW_INSTANTIATE(name, number, Type, compressed)   \
  template std::vector<uint8_t> encode<Type>(const Type& value); \
  template Type decode<Type>(const Message& message);
PRISM_VIEW_MESSAGES(PRISM_VIEW_INSTANTIATE)
#undef PRISM_VIEW_INSTANTIATE

}  // namespace prism::view

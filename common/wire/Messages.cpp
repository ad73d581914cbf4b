#include "wire/Messages.h"

#include "wire/GeometryCodec.h"

#include <climits>
#include <cmath>
#include <cstdio>

#include "image/DisplayBytes.h"
#include "util/InstructionSet.h"
#include "wire/FieldCodec.h"

namespace prism::wire {
namespace {

std::string hex(uint64_t v, int digits) {
  char buffer[24];
  std::snprintf(buffer, sizeof buffer, "0x%0*llX", digits, static_cast<unsigned long long>(v));
  return buffer;
}

// The envelope: magic u32, version u16, type u16, payload size u64 (at kSizeOffset), checksum
// u64 (at kChecksumOffset).
constexpr size_t kSizeOffset = 8, kChecksumOffset = 16;

void writeHeader(ByteWriter& w, MessageType type, uint64_t size, uint64_t checksum) {
  w.writeU32(kMagic);
  w.writeU16(kVersion);
  w.writeU16(static_cast<uint16_t>(type));
  w.writeU64(size);
  w.writeU64(checksum);
}

void putLittleEndian(uint8_t* at, uint64_t v) {
  for (int i = 0; i < 8; ++i) at[i] = static_cast<uint8_t>(v >> (8 * i));
}

template <typename WritePayload>
std::vector<uint8_t> encodeWith(MessageType type, WritePayload writePayload) {
  // The payload is written behind a header whose size and checksum are filled in after it, so a
  // large payload (a photon map, a mesh) is not copied a second time.
  ByteWriter w;
  writeHeader(w, type, 0, 0);
  writePayload(w);
  std::vector<uint8_t> bytes = w.take();
  const size_t size = bytes.size() - kHeaderSize;
  putLittleEndian(bytes.data() + kSizeOffset, size);
  putLittleEndian(bytes.data() + kChecksumOffset,
                  payloadChecksum(bytes.data() + kHeaderSize, size));
  return bytes;
}

void checkSeconds(double seconds, const char* what) {
  if (!(std::isfinite(seconds) && seconds >= 0.0)) {
    throw WireError(std::string("invalid ") + what + " " + std::to_string(seconds));
  }
}

// 0 (radiance), or an exposure at which display bytes come back as they were sent.
void checkDisplayExposure(float exposure) {
  if (exposure == 0.0f && !std::signbit(exposure)) return;
  if (!displayBytesInvertible(exposure)) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", exposure);
    throw WireError(std::string("invalid display exposure ") + text);
  }
}

}  // namespace

uint64_t fnv1a64(const uint8_t* data, size_t size) {
  uint64_t hash = 14695981039346656037ull;
  for (size_t i = 0; i < size; ++i) {
    hash ^= data[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

uint64_t payloadChecksum(const uint8_t* data, size_t size) {
  uint64_t hash = 14695981039346656037ull;
  size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    uint64_t word = 0;
    for (int b = 0; b < 8; ++b) word |= uint64_t{data[i + b]} << (8 * b);  // one load
    hash ^= word;
    hash *= 1099511628211ull;
  }
  for (; i < size; ++i) {
    hash ^= data[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

std::vector<uint8_t> encodeMessage(MessageType type, const std::vector<uint8_t>& payload) {
  ByteWriter w;
  writeHeader(w, type, payload.size(), payloadChecksum(payload.data(), payload.size()));
  std::vector<uint8_t> bytes = w.take();
  bytes.insert(bytes.end(), payload.begin(), payload.end());
  return bytes;
}

namespace {

// Every check of decodeMessage; the type.
MessageType checkEnvelope(const uint8_t* data, size_t size) {
  if (size < kHeaderSize) {
    throw WireError("message too short for a header: " + std::to_string(size) +
                    " bytes, a header needs " + std::to_string(kHeaderSize));
  }
  ByteReader r(data, kHeaderSize);
  const uint32_t magic = r.readU32();
  if (magic != kMagic) {
    throw WireError("bad magic " + hex(magic, 8) + ", expected " + hex(kMagic, 8) +
                    " (\"PRSM\"): not a Prism message");
  }
  const uint16_t version = r.readU16();
  if (version != kVersion) {
    throw WireError("message version " + std::to_string(version) + ", this build speaks " +
                    std::to_string(kVersion));
  }
  const uint16_t type = r.readU16();
  if (!isKnownType(type)) throw WireError("unknown message type " + std::to_string(type));
  const uint64_t declared = r.readU64();
  const size_t actual = size - kHeaderSize;
  if (declared != actual) {
    throw WireError("payload size mismatch: header declares " + std::to_string(declared) +
                    " bytes, message carries " + std::to_string(actual));
  }
  const uint64_t checksum = r.readU64();
  const uint64_t computed = payloadChecksum(data + kHeaderSize, actual);
  if (checksum != computed) {
    throw WireError("payload checksum mismatch: header says " + hex(checksum, 16) +
                    ", payload hashes to " + hex(computed, 16));
  }
  return static_cast<MessageType>(type);
}

}  // namespace

Message decodeMessage(const uint8_t* data, size_t size) {
  const MessageType type = checkEnvelope(data, size);
  return {type, std::vector<uint8_t>(data + kHeaderSize, data + size)};
}

Message decodeMessage(std::vector<uint8_t>&& bytes) {
  const MessageType type = checkEnvelope(bytes.data(), bytes.size());
  bytes.erase(bytes.begin(), bytes.begin() + kHeaderSize);
  return {type, std::move(bytes)};
}

template <WireMessage T>
std::vector<uint8_t> encode(const T& value) {
  return encodeWith(MessageTraits<T>::kType, [&](ByteWriter& w) {
    if constexpr (requires { Fields<T>::wireBytes(value); })
      w.reserveMore(Fields<T>::wireBytes(value));
    writeFields(w, value);
  });
}

// Checks the type, reads the payload, insists it consumed every byte, and puts the message type
// in front of any error so the log says which message was bad.
template <WireMessage T>
T decode(const Message& message) {
  constexpr MessageType expected = MessageTraits<T>::kType;
  if (message.type != expected) {
    throw WireError(std::string("expected a ") + messageTypeName(expected) + " message, got " +
                    messageTypeName(message.type));
  }
  try {
    ByteReader r(message.payload);
    T value;
    readFields(r, value);
    r.expectEnd();
    return value;
  } catch (const WireError& e) {
    throw WireError(std::string(messageTypeName(expected)) + " message: " + e.what());
  }
}

#define PRISM_WIRE_INSTANTIATE(name, number, Type, ...)          \
  template std::vector<uint8_t> encode<Type>(const Type& value); \
  template Type decode<Type>(const Message& message);
PRISM_WIRE_MESSAGES(PRISM_WIRE_INSTANTIATE)
#undef PRISM_WIRE_INSTANTIATE

std::vector<uint8_t> encodePhotonMap(uint32_t pass, const PhotonGatherSettings& gather,
                                     const std::vector<Photon>& photons, bool keep) {
  // PhotonMapMessage's members, in its order, by reference: its field list reads them as it
  // reads the message's own (Messages_test checks that both give the same bytes).
  struct PhotonMapView {
    const uint32_t& pass;
    const PhotonGatherSettings& gather;
    const std::vector<Photon>& photons;
    const bool& keep;
  };
  const PhotonMapView view{pass, gather, photons, keep};
  return encodeWith(MessageType::PhotonMap, [&](ByteWriter& w) {
    PhotonMapMessage::fields(view, [&w](const auto&... field) { (writeField(w, field), ...); });
  });
}

// ---- the checks of the message structs and their parts ---------------------------------------

void Fields<TileRect>::check(const TileRect& rect) {
  const auto& [x, y, width, height] = rect;
  const bool sane = x >= 0 && y >= 0 && width > 0 && height > 0 && int64_t{x} + width <= INT_MAX &&
                    int64_t{y} + height <= INT_MAX && int64_t{width} * height <= INT_MAX;
  if (!sane) {
    throw WireError("invalid tile rectangle at (" + std::to_string(x) + ", " + std::to_string(y) +
                    ") of size " + std::to_string(width) + "x" + std::to_string(height));
  }
}

void Fields<PhotonGatherSettings>::check(const PhotonGatherSettings& gather) {
  const auto& [fixedRadius, k, radius, filter, radiusScale, automaticK] = gather;
  if (k <= 0 || !(radius > 0.0f) || !std::isfinite(radius) || !(radiusScale > 0.0f) ||
      !std::isfinite(radiusScale)) {
    throw WireError("invalid gather settings (k " + std::to_string(k) + ", radius " +
                    std::to_string(radius) + ")");
  }
}

void Fields<RenderView>::check(const RenderView& view) {
  checkDisplayExposure(view.displayExposure);
  if (view.width <= 0 || view.height <= 0 || int64_t{view.width} * view.height > INT_MAX) {
    throw WireError("invalid view size " + std::to_string(view.width) + "x" +
                    std::to_string(view.height));
  }
  if (view.samplesPerPixel <= 0) {
    throw WireError("invalid samples per pixel " + std::to_string(view.samplesPerPixel));
  }
}

void throwBadPhoton(size_t index) {
  throw WireError("photon " + std::to_string(index) + " has a non-finite position or a power " +
                  "that is negative or not finite");
}

void throwBadRadius(size_t index) {
  throw WireError("radius " + std::to_string(index) + " is negative or not finite");
}

void writeTilePixels(ByteWriter& w, const TileResult& result, float exposure) {
  w.writeF32(exposure);
  if (exposure > 0.0f) {
    w.writeU8s(toDisplayBytes(result.pixels, exposure));
  } else {
    w.writeVec3s(result.pixels);
  }
}

void readTilePixels(ByteReader& r, TileResult& result, float& exposure) {
  exposure = r.readF32();
  checkDisplayExposure(exposure);
  if (exposure != 0.0f) {
    const std::vector<uint8_t> bytes = r.readU8s();
    if (bytes.size() % 3 != 0) {
      throw WireError("display bytes of tile " + std::to_string(result.tileIndex) + " are " +
                      std::to_string(bytes.size()) + ", not 3 a pixel");
    }
    result.pixels = fromDisplayBytes(bytes, exposure);
  } else {
    result.pixels = r.readVec3s();
  }
  if (result.pixels.size() != static_cast<size_t>(result.rect.pixelCount())) {
    throw WireError("tile " + std::to_string(result.tileIndex) + " is " +
                    std::to_string(result.rect.width) + "x" + std::to_string(result.rect.height) +
                    " but carries " + std::to_string(result.pixels.size()) + " pixels");
  }
}

void TileJobMessage::check(const TileJobMessage& job) {
  const uint8_t terms = job.terms;
  const bool bothCaustics = (terms & kTermCaustics) && (terms & kTermCausticMap);
  if (terms == 0 || terms > (kTermDirect | kTermCaustics | kTermCausticMap) || bothCaustics) {
    throw WireError("invalid light terms " + std::to_string(terms));
  }
}

void TileResultMessage::check(const TileResultMessage& message) {
  checkSeconds(message.result.seconds, "tile render time");
}

void ReadyMessage::check(const ReadyMessage& ready) {
  checkSeconds(ready.buildSeconds, "scene build time");
  if (ready.startSeconds != -1.0) checkSeconds(ready.startSeconds, "start time");
  checkSeconds(ready.mpiInitSeconds, "MPI_Init time");
  if (ready.threads < 0) throw WireError("invalid thread count " + std::to_string(ready.threads));
}

void SceneAcceptedMessage::check(const SceneAcceptedMessage& accepted) {
  for (int32_t n : {accepted.threads, accepted.cores, accepted.ranksOnNode}) {
    if (n < 1) throw WireError("invalid count " + std::to_string(n) + " in SceneAccepted");
  }
}

void HelloMessage::check(const HelloMessage& hello) {
  const uint32_t known = maskOf(InstructionSet::Baseline) | maskOf(InstructionSet::V2) |
                         maskOf(InstructionSet::V3) | maskOf(InstructionSet::V4);
  if ((hello.instructionSets & ~known) != 0 ||
      !(hello.instructionSets & maskOf(InstructionSet::Baseline))) {
    throw WireError("invalid instruction sets " + hex(hello.instructionSets, 8));
  }
  if (hello.cpu.size() > prism::kMaxCpuNameBytes) {
    throw WireError("CPU name of " + std::to_string(hello.cpu.size()) + " bytes (at most " +
                    std::to_string(prism::kMaxCpuNameBytes) + ")");
  }
}

void ViewMessage::check(const ViewMessage& message) {
  if (message.liveFrom > message.frame) {
    throw WireError("view of frame " + std::to_string(message.frame) + " keeps a later frame " +
                    std::to_string(message.liveFrom) + " running");
  }
}

void PhotonJobMessage::check(const PhotonJobMessage& job) {
  if (job.first + job.count < job.first) throw WireError("photon range overflows");
  if (job.first + job.count > job.photonsPerPass) {
    throw WireError("photon range exceeds the budget");
  }
}

void PhotonShareMessage::check(const PhotonShareMessage& share) {
  if (share.photons.size() != share.stats.stored) {
    throw WireError("carries " + std::to_string(share.photons.size()) + " photons but reports " +
                    std::to_string(share.stats.stored) + " stored");
  }
}

void PhotonRadiiJobMessage::check(const PhotonRadiiJobMessage& job) {
  if (job.first + job.count < job.first) throw WireError("radii range overflows");
}

}  // namespace prism::wire

#include "wire/Messages.h"

#include <climits>
#include <cmath>
#include <cstdio>

#include "image/DisplayBytes.h"
#include "wire/SceneCodec.h"

namespace prism::wire {
namespace {

std::string hex(uint64_t v, int digits) {
  char buffer[24];
  std::snprintf(buffer, sizeof buffer, "0x%0*llX", digits, static_cast<unsigned long long>(v));
  return buffer;
}

bool isKnownType(uint16_t raw) {
  return raw >= static_cast<uint16_t>(MessageType::Scene) &&
         raw <= static_cast<uint16_t>(MessageType::PhotonRadii);
}

// Checks the type, runs readPayload over the payload, insists it consumed every byte, and puts
// the message type in front of any error so the log says which message was bad.
template <typename ReadPayload>
auto decodePayload(const Message& message, MessageType expected, ReadPayload readPayload) {
  if (message.type != expected) {
    throw WireError(std::string("expected a ") + messageTypeName(expected) + " message, got " +
                    messageTypeName(message.type));
  }
  try {
    ByteReader r(message.payload);
    auto value = readPayload(r);
    r.expectEnd();
    return value;
  } catch (const WireError& e) {
    throw WireError(std::string(messageTypeName(expected)) + " message: " + e.what());
  }
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
  putLittleEndian(bytes.data() + kChecksumOffset, fnv1a64(bytes.data() + kHeaderSize, size));
  return bytes;
}

void writeRect(ByteWriter& w, const TileRect& rect) {
  const auto& [x, y, width, height] = rect;
  w.writeI32(x);
  w.writeI32(y);
  w.writeI32(width);
  w.writeI32(height);
}

// A tile must be non-empty, start inside the first quadrant, and have a pixel count and far
// corner that fit in an int, since TileRect does its arithmetic in int.
TileRect readRect(ByteReader& r) {
  TileRect rect;
  auto& [x, y, width, height] = rect;
  x = r.readI32();
  y = r.readI32();
  width = r.readI32();
  height = r.readI32();
  const bool sane = x >= 0 && y >= 0 && width > 0 && height > 0 && int64_t{x} + width <= INT_MAX &&
                    int64_t{y} + height <= INT_MAX && int64_t{width} * height <= INT_MAX;
  if (!sane) {
    throw WireError("invalid tile rectangle at (" + std::to_string(x) + ", " + std::to_string(y) +
                    ") of size " + std::to_string(width) + "x" + std::to_string(height));
  }
  return rect;
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

const char* messageTypeName(MessageType type) {
  switch (type) {
    case MessageType::Scene:
      return "Scene";
    case MessageType::Ready:
      return "Ready";
    case MessageType::TileJob:
      return "TileJob";
    case MessageType::TileResult:
      return "TileResult";
    case MessageType::Shutdown:
      return "Shutdown";
    case MessageType::Error:
      return "Error";
    case MessageType::Progress:
      return "Progress";
    case MessageType::View:
      return "View";
    case MessageType::Echo:
      return "Echo";
    case MessageType::PhotonCancel:
      return "PhotonCancel";
    case MessageType::PhotonJob:
      return "PhotonJob";
    case MessageType::PhotonShare:
      return "PhotonShare";
    case MessageType::PhotonMap:
      return "PhotonMap";
    case MessageType::PhotonMapAgain:
      return "PhotonMapAgain";
    case MessageType::PhotonRadiiJob:
      return "PhotonRadiiJob";
    case MessageType::PhotonRadiiShare:
      return "PhotonRadiiShare";
    case MessageType::PhotonRadii:
      return "PhotonRadii";
  }
  return "unknown";
}

uint64_t fnv1a64(const uint8_t* data, size_t size) {
  uint64_t hash = 14695981039346656037ull;
  for (size_t i = 0; i < size; ++i) {
    hash ^= data[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

std::vector<uint8_t> encodeMessage(MessageType type, const std::vector<uint8_t>& payload) {
  ByteWriter w;
  writeHeader(w, type, payload.size(), fnv1a64(payload.data(), payload.size()));
  std::vector<uint8_t> bytes = w.take();
  bytes.insert(bytes.end(), payload.begin(), payload.end());
  return bytes;
}

Message decodeMessage(const uint8_t* data, size_t size) {
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
  const uint64_t computed = fnv1a64(data + kHeaderSize, actual);
  if (checksum != computed) {
    throw WireError("payload checksum mismatch: header says " + hex(checksum, 16) +
                    ", payload hashes to " + hex(computed, 16));
  }
  return {static_cast<MessageType>(type),
          std::vector<uint8_t>(data + kHeaderSize, data + kHeaderSize + actual)};
}

std::vector<uint8_t> encodeScene(const SceneDescription& scene) {
  return encodeWith(MessageType::Scene, [&](ByteWriter& w) { writeScene(w, scene); });
}

SceneDescription decodeScene(const Message& message) {
  return decodePayload(message, MessageType::Scene, readScene);
}

std::vector<uint8_t> encodeTileJob(const TileJobMessage& job) {
  return encodeWith(MessageType::TileJob, [&](ByteWriter& w) {
    const auto& [frame, tileIndex, rect, pass, terms] = job;
    w.writeU32(frame);
    w.writeU32(tileIndex);
    writeRect(w, rect);
    w.writeU32(pass);
    w.writeU8(terms);
  });
}

TileJobMessage decodeTileJob(const Message& message) {
  return decodePayload(message, MessageType::TileJob, [](ByteReader& r) {
    TileJobMessage job;
    auto& [frame, tileIndex, rect, pass, terms] = job;
    frame = r.readU32();
    tileIndex = r.readU32();
    rect = readRect(r);
    pass = r.readU32();
    terms = r.readU8();
    // Any non-empty set of the three, but never both kinds of caustics.
    const bool bothCaustics = (terms & kTermCaustics) && (terms & kTermCausticMap);
    if (terms == 0 || terms > (kTermDirect | kTermCaustics | kTermCausticMap) || bothCaustics) {
      throw WireError("invalid light terms " + std::to_string(terms));
    }
    return job;
  });
}

std::vector<uint8_t> encodeTileResult(const TileResultMessage& message) {
  return encodeWith(MessageType::TileResult, [&](ByteWriter& w) {
    const auto& [frame, result, displayExposure] = message;
    const auto& [tileIndex, rect, pixels, rays, seconds] = result;
    const auto& [primary, shadow, secondary, nonFinite] = rays;
    w.writeU32(frame);
    w.writeU32(tileIndex);
    writeRect(w, rect);
    w.writeF32(displayExposure);
    if (displayExposure > 0.0f) {
      w.writeU8s(toDisplayBytes(pixels, displayExposure));
    } else {
      w.writeVec3s(pixels);
    }
    w.writeU64(primary);
    w.writeU64(shadow);
    w.writeU64(secondary);
    w.writeU64(nonFinite);
    w.writeF64(seconds);
  });
}

TileResultMessage decodeTileResult(const Message& message) {
  return decodePayload(message, MessageType::TileResult, [](ByteReader& r) {
    TileResultMessage m;
    auto& [frame, result, displayExposure] = m;
    auto& [tileIndex, rect, pixels, rays, seconds] = result;
    auto& [primary, shadow, secondary, nonFinite] = rays;
    frame = r.readU32();
    tileIndex = r.readU32();
    rect = readRect(r);
    displayExposure = r.readF32();
    checkDisplayExposure(displayExposure);
    if (displayExposure != 0.0f) {
      const std::vector<uint8_t> bytes = r.readU8s();
      if (bytes.size() % 3 != 0) {
        throw WireError("display bytes of tile " + std::to_string(tileIndex) + " are " +
                        std::to_string(bytes.size()) + ", not 3 a pixel");
      }
      pixels = fromDisplayBytes(bytes, displayExposure);
    } else {
      pixels = r.readVec3s();
    }
    if (pixels.size() != static_cast<size_t>(rect.pixelCount())) {
      throw WireError("tile " + std::to_string(tileIndex) + " is " + std::to_string(rect.width) +
                      "x" + std::to_string(rect.height) + " but carries " +
                      std::to_string(pixels.size()) + " pixels");
    }
    primary = r.readU64();
    shadow = r.readU64();
    secondary = r.readU64();
    nonFinite = r.readU64();
    seconds = r.readF64();
    checkSeconds(seconds, "tile render time");
    return m;
  });
}

std::vector<uint8_t> encodeReady(const ReadyMessage& ready) {
  return encodeWith(MessageType::Ready, [&](ByteWriter& w) {
    const auto& [buildSeconds, threads, startSeconds, mpiInitSeconds] = ready;
    w.writeF64(buildSeconds);
    w.writeI32(threads);
    w.writeF64(startSeconds);
    w.writeF64(mpiInitSeconds);
  });
}

ReadyMessage decodeReady(const Message& message) {
  return decodePayload(message, MessageType::Ready, [](ByteReader& r) {
    ReadyMessage ready;
    auto& [buildSeconds, threads, startSeconds, mpiInitSeconds] = ready;
    buildSeconds = r.readF64();
    threads = r.readI32();
    startSeconds = r.readF64();
    mpiInitSeconds = r.readF64();
    checkSeconds(buildSeconds, "scene build time");
    if (startSeconds != -1.0) checkSeconds(startSeconds, "start time");
    checkSeconds(mpiInitSeconds, "MPI_Init time");
    if (threads < 0) throw WireError("invalid thread count " + std::to_string(threads));
    return ready;
  });
}

std::vector<uint8_t> encodeError(const ErrorMessage& error) {
  return encodeWith(MessageType::Error, [&](ByteWriter& w) { w.writeString(error.text); });
}

ErrorMessage decodeError(const Message& message) {
  return decodePayload(message, MessageType::Error,
                       [](ByteReader& r) { return ErrorMessage{r.readString()}; });
}

std::vector<uint8_t> encodeEcho(const EchoMessage& echo) {
  return encodeWith(MessageType::Echo, [&](ByteWriter& w) {
    w.writeU32(echo.sequence);
    w.writeString(echo.padding);
  });
}

EchoMessage decodeEcho(const Message& message) {
  return decodePayload(message, MessageType::Echo, [](ByteReader& r) {
    EchoMessage echo;
    echo.sequence = r.readU32();
    echo.padding = r.readString();
    return echo;
  });
}

std::vector<uint8_t> encodePhotonMapAgain(const PhotonMapAgainMessage& again) {
  return encodeWith(MessageType::PhotonMapAgain, [&](ByteWriter& w) {
    w.writeU32(again.pass);
    w.writeU32(again.keptPass);
  });
}

PhotonMapAgainMessage decodePhotonMapAgain(const Message& message) {
  return decodePayload(message, MessageType::PhotonMapAgain, [](ByteReader& r) {
    PhotonMapAgainMessage again;
    again.pass = r.readU32();
    again.keptPass = r.readU32();
    return again;
  });
}

std::vector<uint8_t> encodePhotonCancel(const PhotonCancelMessage& cancel) {
  return encodeWith(MessageType::PhotonCancel, [&](ByteWriter& w) { w.writeU32(cancel.pass); });
}

PhotonCancelMessage decodePhotonCancel(const Message& message) {
  return decodePayload(message, MessageType::PhotonCancel,
                       [](ByteReader& r) { return PhotonCancelMessage{r.readU32()}; });
}

std::vector<uint8_t> encodeShutdown() {
  return encodeMessage(MessageType::Shutdown, {});
}

void decodeShutdown(const Message& message) {
  decodePayload(message, MessageType::Shutdown, [](ByteReader&) { return 0; });
}

std::vector<uint8_t> encodeProgress(const ProgressMessage& progress) {
  return encodeWith(MessageType::Progress, [&](ByteWriter& w) {
    const auto& [frame, jobsReceived, heldTiles] = progress;
    w.writeU32(frame);
    w.writeU64(jobsReceived);
    w.writeU32s(heldTiles);
  });
}

ProgressMessage decodeProgress(const Message& message) {
  return decodePayload(message, MessageType::Progress, [](ByteReader& r) {
    ProgressMessage progress;
    auto& [frame, jobsReceived, heldTiles] = progress;
    frame = r.readU32();
    jobsReceived = r.readU64();
    heldTiles = r.readU32s();
    return progress;
  });
}

std::vector<uint8_t> encodeView(const ViewMessage& message) {
  return encodeWith(MessageType::View, [&](ByteWriter& w) {
    const auto& [frame, liveFrom, view] = message;
    const auto& [camera, width, height, samplesPerPixel, seed, debugView, causticMapBlur,
                 jitterSingleSample, displayExposure] = view;
    w.writeU32(frame);
    w.writeU32(liveFrom);
    writeCamera(w, camera);
    w.writeI32(width);
    w.writeI32(height);
    w.writeI32(samplesPerPixel);
    w.writeU64(seed);
    w.writeU32(static_cast<uint32_t>(debugView));
    w.writeU8(causticMapBlur ? 1 : 0);
    w.writeU8(jitterSingleSample ? 1 : 0);
    w.writeF32(displayExposure);
  });
}

ViewMessage decodeView(const Message& message) {
  return decodePayload(message, MessageType::View, [](ByteReader& r) {
    ViewMessage m;
    auto& [frame, liveFrom, view] = m;
    auto& [camera, width, height, samplesPerPixel, seed, debugView, causticMapBlur,
           jitterSingleSample, displayExposure] = view;
    frame = r.readU32();
    liveFrom = r.readU32();
    if (liveFrom > frame) {
      throw WireError("view of frame " + std::to_string(frame) + " keeps a later frame " +
                      std::to_string(liveFrom) + " running");
    }
    camera = readCamera(r);
    width = r.readI32();
    height = r.readI32();
    samplesPerPixel = r.readI32();
    seed = r.readU64();
    const uint32_t rawView = r.readU32();
    const uint8_t blur = r.readU8();
    if (blur > 1) throw WireError("invalid caustic-map blur flag " + std::to_string(blur));
    causticMapBlur = blur == 1;
    const uint8_t jitter = r.readU8();
    if (jitter > 1) throw WireError("invalid jitter flag " + std::to_string(jitter));
    jitterSingleSample = jitter == 1;
    displayExposure = r.readF32();
    checkDisplayExposure(displayExposure);
    if (width <= 0 || height <= 0 || int64_t{width} * height > INT_MAX) {
      throw WireError("invalid view size " + std::to_string(width) + "x" + std::to_string(height));
    }
    if (samplesPerPixel <= 0) {
      throw WireError("invalid samples per pixel " + std::to_string(samplesPerPixel));
    }
    // DebugView is a byte: compare before trusting the cast, or 256 would read as Image (found
    // by the wire fuzzer).
    const auto known = static_cast<DebugView>(rawView);
    if (static_cast<uint32_t>(known) == rawView) {
      switch (known) {
        case DebugView::Image:
        case DebugView::Normals:
          debugView = known;
          return m;
      }
    }
    throw WireError("invalid debug view " + std::to_string(rawView));
  });
}

namespace {

constexpr size_t kPhotonBytes = 28;
// A photon's wire form is position, power, direction: its memory where the wire order is native
// (no padding), so a map of millions is copied in one go (11.6 MB: 33-50 ms number by number).
constexpr bool kPhotonIsItsWireForm = kWireOrderIsNative && sizeof(Photon) == kPhotonBytes &&
                                      sizeof(Vec3) == 12 && sizeof(Photon::direction) == 4;
constexpr size_t kPhotonBlock = 1024;  // photons copied in one go (28 KiB)

void writePhotons(ByteWriter& w, const std::vector<Photon>& photons) {
  w.writeCount(photons.size());
  if constexpr (kPhotonIsItsWireForm) {
    w.writeRaw(photons.data(), photons.size() * kPhotonBytes);
    return;
  }
  for (const Photon& p : photons) {
    w.writeVec3(p.position);
    w.writeVec3(p.power);
    w.writeU16(p.direction[0]);
    w.writeU16(p.direction[1]);
  }
}

std::vector<Photon> readPhotons(ByteReader& r) {
  const size_t count = r.readCount(kPhotonBytes);
  std::vector<Photon> photons(count);
  for (size_t i = 0; i < count; ++i) {
    Photon& p = photons[i];
    if constexpr (kPhotonIsItsWireForm) {
      // A block at a time, checked while it is still in the cache.
      if (i % kPhotonBlock == 0) {
        r.readRaw(&p, std::min(kPhotonBlock, count - i) * kPhotonBytes);
      }
    } else {
      p.position = r.readVec3();
      p.power = r.readVec3();
      p.direction[0] = r.readU16();
      p.direction[1] = r.readU16();
    }
    if (!isFinite(p.position) || !isFinite(p.power) || p.power.x < 0.0f || p.power.y < 0.0f ||
        p.power.z < 0.0f) {
      throw WireError("photon " + std::to_string(i) + " has a non-finite position or a power " +
                      "that is negative or not finite");
    }
  }
  return photons;
}

// Gather radii: finite and not negative (a photon without k neighbours has its cap).
std::vector<float> readRadii(ByteReader& r) {
  std::vector<float> radii = r.readF32s();
  for (size_t i = 0; i < radii.size(); ++i) {
    if (!(radii[i] >= 0.0f) || !std::isfinite(radii[i])) {
      throw WireError("radius " + std::to_string(i) + " is negative or not finite");
    }
  }
  return radii;
}

}  // namespace

std::vector<uint8_t> encodePhotonJob(const PhotonJobMessage& job) {
  return encodeWith(MessageType::PhotonJob, [&](ByteWriter& w) {
    const auto& [pass, first, count, photonsPerPass] = job;
    w.writeU32(pass);
    w.writeU64(first);
    w.writeU64(count);
    w.writeU64(photonsPerPass);
  });
}

PhotonJobMessage decodePhotonJob(const Message& message) {
  return decodePayload(message, MessageType::PhotonJob, [](ByteReader& r) {
    PhotonJobMessage job;
    auto& [pass, first, count, photonsPerPass] = job;
    pass = r.readU32();
    first = r.readU64();
    count = r.readU64();
    photonsPerPass = r.readU64();
    if (first + count < first) throw WireError("photon range overflows");
    if (first + count > photonsPerPass) throw WireError("photon range exceeds the budget");
    return job;
  });
}

std::vector<uint8_t> encodePhotonShare(const PhotonShareMessage& share) {
  return encodeWith(MessageType::PhotonShare, [&](ByteWriter& w) {
    const auto& [pass, first, count, stats, seconds, photons] = share;
    const auto& [emitted, stored, missed, absorbed] = stats;
    w.writeU32(pass);
    w.writeU64(first);
    w.writeU64(count);
    w.writeU64(emitted);
    w.writeU64(stored);
    w.writeU64(missed);
    w.writeU64(absorbed);
    w.writeF64(seconds);
    writePhotons(w, photons);
  });
}

PhotonShareMessage decodePhotonShare(const Message& message) {
  return decodePayload(message, MessageType::PhotonShare, [](ByteReader& r) {
    PhotonShareMessage share;
    auto& [pass, first, count, stats, seconds, photons] = share;
    auto& [emitted, stored, missed, absorbed] = stats;
    pass = r.readU32();
    first = r.readU64();
    count = r.readU64();
    emitted = r.readU64();
    stored = r.readU64();
    missed = r.readU64();
    absorbed = r.readU64();
    seconds = r.readF64();
    photons = readPhotons(r);
    if (photons.size() != stored) {
      throw WireError("carries " + std::to_string(photons.size()) + " photons but reports " +
                      std::to_string(stored) + " stored");
    }
    return share;
  });
}

std::vector<uint8_t> encodePhotonMap(const PhotonMapMessage& map) {
  const auto& [pass, gather, photons, keep] = map;
  return encodePhotonMap(pass, gather, photons, keep);
}

std::vector<uint8_t> encodePhotonMap(uint32_t pass, const PhotonGatherSettings& gather,
                                     const std::vector<Photon>& photons, bool keep) {
  return encodeWith(MessageType::PhotonMap, [&](ByteWriter& w) {
    const auto& [fixedRadius, k, radius, filter, radiusScale, automaticK] = gather;
    w.writeU32(pass);
    w.writeBool(fixedRadius);
    w.writeI32(k);
    w.writeF32(radius);
    w.writeU32(static_cast<uint32_t>(filter));
    w.writeF32(radiusScale);
    w.writeBool(automaticK);
    w.writeBool(keep);
    writePhotons(w, photons);
  });
}

PhotonMapMessage decodePhotonMap(const Message& message) {
  return decodePayload(message, MessageType::PhotonMap, [](ByteReader& r) {
    PhotonMapMessage map;
    auto& [pass, gather, photons, keep] = map;
    auto& [fixedRadius, k, radius, filter, radiusScale, automaticK] = gather;
    pass = r.readU32();
    fixedRadius = r.readBool();
    k = r.readI32();
    radius = r.readF32();
    const uint32_t rawFilter = r.readU32();
    if (rawFilter > static_cast<uint32_t>(PhotonFilter::Epanechnikov)) {
      throw WireError("invalid photon filter " + std::to_string(rawFilter));
    }
    filter = static_cast<PhotonFilter>(rawFilter);
    radiusScale = r.readF32();
    automaticK = r.readBool();
    keep = r.readBool();
    if (k <= 0 || !(radius > 0.0f) || !std::isfinite(radius) || !(radiusScale > 0.0f) ||
        !std::isfinite(radiusScale)) {
      throw WireError("invalid gather settings (k " + std::to_string(k) + ", radius " +
                      std::to_string(radius) + ")");
    }
    photons = readPhotons(r);
    return map;
  });
}

std::vector<uint8_t> encodePhotonRadiiJob(const PhotonRadiiJobMessage& job) {
  return encodeWith(MessageType::PhotonRadiiJob, [&](ByteWriter& w) {
    w.writeU32(job.pass);
    w.writeU64(job.first);
    w.writeU64(job.count);
  });
}

PhotonRadiiJobMessage decodePhotonRadiiJob(const Message& message) {
  return decodePayload(message, MessageType::PhotonRadiiJob, [](ByteReader& r) {
    PhotonRadiiJobMessage job;
    job.pass = r.readU32();
    job.first = r.readU64();
    job.count = r.readU64();
    if (job.first + job.count < job.first) throw WireError("radii range overflows");
    return job;
  });
}

std::vector<uint8_t> encodePhotonRadiiShare(const PhotonRadiiShareMessage& share) {
  return encodeWith(MessageType::PhotonRadiiShare, [&](ByteWriter& w) {
    w.writeU32(share.pass);
    w.writeU64(share.first);
    w.writeF32s(share.radii);
  });
}

PhotonRadiiShareMessage decodePhotonRadiiShare(const Message& message) {
  return decodePayload(message, MessageType::PhotonRadiiShare, [](ByteReader& r) {
    PhotonRadiiShareMessage share;
    share.pass = r.readU32();
    share.first = r.readU64();
    share.radii = readRadii(r);
    return share;
  });
}

std::vector<uint8_t> encodePhotonRadii(const PhotonRadiiMessage& radii) {
  return encodeWith(MessageType::PhotonRadii, [&](ByteWriter& w) {
    w.writeU32(radii.pass);
    w.writeF32s(radii.radii);
  });
}

PhotonRadiiMessage decodePhotonRadii(const Message& message) {
  return decodePayload(message, MessageType::PhotonRadii, [](ByteReader& r) {
    PhotonRadiiMessage radii;
    radii.pass = r.readU32();
    radii.radii = readRadii(r);
    return radii;
  });
}

}  // namespace prism::wire

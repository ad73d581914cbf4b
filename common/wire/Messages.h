// The messages the master and the slaves exchange, as bytes. Each message is an envelope
// (magic, version, type, payload size, payload checksum) around a payload; decoding checks the
// envelope and then the payload strictly, and throws WireError naming what is wrong. No MPI
// here: the transport moves the bytes, this file gives them meaning.
//
// Each message is a struct that lists its fields once (wire/Fields.h); encode, decode and
// sameFields follow from the list. PRISM_WIRE_MESSAGES below is the one list of message types:
// the MessageType enumeration, its names, isKnownType, each type's direction, phase and role
// (kindOf) and the per-type dispatch come from it.
// Adding a message takes its struct (fields, list, any check) here and a line in that list.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "caustics/Photon.h"
#include "caustics/PhotonGatherSettings.h"
#include "caustics/PhotonTraceStats.h"
#include "render/RenderView.h"
#include "render/Tile.h"
#include "scene/SceneDescription.h"
#include "util/InstructionSet.h"
#include "wire/ByteBuffer.h"
#include "wire/Fields.h"
#include "wire/MessageParts.h"
#include "wire/SceneCodec.h"

namespace prism {
// A Geometry message carries a built geometry; its field lists are in wire/GeometryCodec.h,
// which only the code that sends or receives one includes, so the other messages' users do not
// reach the acceleration structures.
class SceneGeometry;
}  // namespace prism

namespace prism::wire {

inline constexpr uint32_t kMagic = 0x4D535250;  // "PRSM" little-endian
// Bumped whenever any message's bytes change, so builds that would misread each other refuse
// each other's messages instead.
inline constexpr uint16_t kVersion = 16;
// magic u32, version u16, type u16, payload size u64, payloadChecksum of the payload u64.
inline constexpr size_t kHeaderSize = 24;

// Every message type: its name, its number on the wire (never reused), the struct it carries,
// and what it is to a run (the enumerations below): which way it goes, in which phase, and its
// role.
#define PRISM_WIRE_MESSAGES(X)                                            \
  X(Scene, 1, SceneDescription, ToSlave, SetUp, Control)                  \
  X(Ready, 2, ReadyMessage, ToMaster, SetUp, Control)                     \
  X(TileJob, 3, TileJobMessage, ToSlave, Run, Work)                       \
  X(TileResult, 4, TileResultMessage, ToMaster, Run, Answer)              \
  X(Shutdown, 5, ShutdownMessage, BothWays, ShutDown, Control)            \
  X(Error, 6, ErrorMessage, BothWays, AnyPhase, Control)                  \
  X(Progress, 7, ProgressMessage, ToMaster, Run, Answer)                  \
  X(PhotonJob, 8, PhotonJobMessage, ToSlave, Run, Work)                   \
  X(PhotonShare, 9, PhotonShareMessage, ToMaster, Run, Answer)            \
  X(PhotonMap, 10, PhotonMapMessage, ToSlave, Run, Control)               \
  X(View, 11, ViewMessage, ToSlave, Run, Control)                         \
  X(Echo, 12, EchoMessage, BothWays, Run, Control)                        \
  X(PhotonCancel, 13, PhotonCancelMessage, ToSlave, Run, Control)         \
  X(PhotonMapAgain, 14, PhotonMapAgainMessage, ToSlave, Run, Control)     \
  X(PhotonRadiiJob, 15, PhotonRadiiJobMessage, ToSlave, Run, Work)        \
  X(PhotonRadiiShare, 16, PhotonRadiiShareMessage, ToMaster, Run, Answer) \
  X(PhotonRadii, 17, PhotonRadiiMessage, ToSlave, Run, Control)           \
  X(Hello, 18, HelloMessage, ToMaster, SetUp, Control)                    \
  X(SceneAccepted, 19, SceneAcceptedMessage, ToMaster, SetUp, Control)    \
  X(BuildGeometry, 20, BuildGeometryMessage, ToSlave, SetUp, Control)     \
  X(Geometry, 21, SceneGeometry, ToSlave, SetUp, Control)

// Which way a message goes: rank 0 to a slave, a slave to rank 0, or either.
enum class Direction : uint8_t { ToSlave, ToMaster, BothWays };
// When in a run: while the job is set up (Hello to Ready), while it runs (frames, photon passes,
// probes), at its end, or whenever something goes wrong.
enum class Phase : uint8_t { SetUp, Run, ShutDown, AnyPhase };
// Work: a piece a slave is leased and answers for; Answer: what a slave sends back for its work
// (results, shares, the heartbeat); Control: everything else (the scene, settings, the end).
enum class Role : uint8_t { Work, Answer, Control };

enum class MessageType : uint16_t {
#define PRISM_WIRE_ENUMERATOR(name, number, Type, ...) name = number,
  PRISM_WIRE_MESSAGES(PRISM_WIRE_ENUMERATOR)
#undef PRISM_WIRE_ENUMERATOR
};

// "Scene", "TileResult", ...; "unknown" for values outside the enumeration.
constexpr const char* messageTypeName(MessageType type) {
  switch (type) {
#define PRISM_WIRE_NAME(name, number, Type, ...) \
  case MessageType::name:                        \
    return #name;
    PRISM_WIRE_MESSAGES(PRISM_WIRE_NAME)
#undef PRISM_WIRE_NAME
  }
  return "unknown";
}

struct MessageKind {
  Direction direction;
  Phase phase;
  Role role;
};

// The list's direction, phase and role of a type; throws std::out_of_range for one outside it.
constexpr MessageKind kindOf(MessageType type) {
  switch (type) {
#define PRISM_WIRE_KIND(name, number, Type, direction, phase, role) \
  case MessageType::name:                                           \
    return {Direction::direction, Phase::phase, Role::role};
    PRISM_WIRE_MESSAGES(PRISM_WIRE_KIND)
#undef PRISM_WIRE_KIND
  }
  throw std::out_of_range("unknown message type");
}

// Whether a message of the type may travel `way` (ToSlave or ToMaster).
constexpr bool goesTo(MessageType type, Direction way) {
  const Direction direction = kindOf(type).direction;
  return direction == Direction::BothWays || direction == way;
}
// Whether it may arrive while the run is in `phase` (Error may at any time).
constexpr bool belongsTo(MessageType type, Phase phase) {
  const Phase own = kindOf(type).phase;
  return own == Phase::AnyPhase || own == phase;
}

// Past the highest number in the list: the first a new message can take.
constexpr uint16_t firstUnusedTypeNumber() {
  uint16_t highest = 0;
#define PRISM_WIRE_HIGHEST(name, number, Type, ...) highest = number > highest ? number : highest;
  PRISM_WIRE_MESSAGES(PRISM_WIRE_HIGHEST)
#undef PRISM_WIRE_HIGHEST
  return static_cast<uint16_t>(highest + 1);
}

constexpr bool isKnownType(uint16_t raw) {
  switch (raw) {
#define PRISM_WIRE_NUMBER(name, number, Type, ...) case number:
    PRISM_WIRE_MESSAGES(PRISM_WIRE_NUMBER)
#undef PRISM_WIRE_NUMBER
    return true;
  }
  return false;
}

// FNV-1a, 64 bit: detects every single-byte change, which is what a checksum here is for.
uint64_t fnv1a64(const uint8_t* data, size_t size);
// The envelope's checksum: FNV-1a over the payload's little-endian 64-bit words, then its last
// bytes one by one. Any one changed word (so any one changed byte) changes it, as byte-wise
// FNV-1a does, at an eighth of the multiplications: byte-wise, a 323 MiB geometry took 0.6 s to
// hash on each side.
uint64_t payloadChecksum(const uint8_t* data, size_t size);

std::vector<uint8_t> encodeMessage(MessageType type, const std::vector<uint8_t>& payload);

struct Message {
  MessageType type;
  std::vector<uint8_t> payload;
};

// Checks the envelope: long enough for a header, magic, version, known type, declared payload
// size equal to the bytes present, checksum. Throws WireError.
Message decodeMessage(const uint8_t* data, size_t size);
inline Message decodeMessage(const std::vector<uint8_t>& bytes) {
  return decodeMessage(bytes.data(), bytes.size());
}
// The same, the payload taking over the bytes' memory instead of a copy (a broadcast geometry
// is hundreds of megabytes).
Message decodeMessage(std::vector<uint8_t>&& bytes);

// Bits of TileJobMessage::terms: what the tile adds up (see render/WhittedIntegrator.h).
inline constexpr uint8_t kTermDirect = 1;
inline constexpr uint8_t kTermCaustics = 2;  // with the photon map of `pass`
// With the caustic maps the rank builds from the scene, blurred as the current view says.
inline constexpr uint8_t kTermCausticMap = 4;

struct TileJobMessage {
  uint32_t frame = 0;
  uint32_t tileIndex = 0;
  TileRect rect;
  uint32_t pass = 0;
  uint8_t terms = kTermDirect;
  PRISM_WIRE_FIELDS(frame, tileIndex, rect, pass, terms)
  // Any non-empty set of the three terms, but never both kinds of caustics.
  static void check(const TileJobMessage& job);
};

// Master to slave: trace photons [first, first + count) of a pass and send them back.
// photonsPerPass is the budget the master's tracer was planned with: photon powers and the
// split between lights depend on it, so the slave plans its tracer with the same budget.
struct PhotonJobMessage {
  uint32_t pass = 0;
  uint64_t first = 0;
  uint64_t count = 0;
  uint64_t photonsPerPass = 0;
  PRISM_WIRE_FIELDS(pass, first, count, photonsPerPass)
  static void check(const PhotonJobMessage& job);  // the range fits in the budget
};

// Master to slave: stop the PhotonJob or PhotonRadiiJob of this pass and send nothing for it
// (the camera moved or the viewer stopped: rank 0 dropped the pass).
struct PhotonCancelMessage {
  uint32_t pass = 0;
  PRISM_WIRE_FIELDS(pass)
};

// Slave to master: the photons it stored for a PhotonJob, in photon-index order.
struct PhotonShareMessage {
  uint32_t pass = 0;
  uint64_t first = 0;
  uint64_t count = 0;
  PhotonTraceStats stats;
  double seconds = 0;
  std::vector<Photon> photons;
  static void fields(auto& self, auto&& visit) {
    auto& [pass, first, count, stats, seconds, photons] = self;
    visit(pass, first, count, stats, seconds, each(photons, CheckPhoton{}));
  }
  static void check(const PhotonShareMessage& share);  // as many photons as stats.stored
};

// Master to slave: every photon of a pass, and how to gather from them; tiles of that pass
// with kTermCaustics use it. keep: the master may name this map again (PhotonMapAgain), so the
// slave keeps it, with its radii, beside the maps that follow until the next one to keep.
// Where the gather needs per-photon radii (PhotonGather::needsRadii), the slave gathers only
// once PhotonRadii brings them, and may be asked first to find a share (PhotonRadiiJob).
struct PhotonMapMessage {
  uint32_t pass = 0;
  PhotonGatherSettings gather;
  std::vector<Photon> photons;
  bool keep = false;
  static void fields(auto& self, auto&& visit) {  // the keep flag before the photons
    auto& [pass, gather, photons, keep] = self;
    visit(pass, gather, keep, each(photons, CheckPhoton{}));
  }
};

// Master to slave: find the radii of positions [first, first + count) of the spatial order of
// the map of `pass` (caustics/PhotonRadii.h) and send them back.
struct PhotonRadiiJobMessage {
  uint32_t pass = 0;
  uint64_t first = 0;
  uint64_t count = 0;
  PRISM_WIRE_FIELDS(pass, first, count)
  static void check(const PhotonRadiiJobMessage& job);  // the range does not overflow
};

// Slave to master: the radii of a PhotonRadiiJob, in spatial order from `first`.
struct PhotonRadiiShareMessage {
  uint32_t pass = 0;
  uint64_t first = 0;
  std::vector<float> radii;
  static void fields(auto& self, auto&& visit) {
    auto& [pass, first, radii] = self;
    visit(pass, first, each(radii, CheckRadius{}));
  }
};

// Master to slave: every photon's radius of the map of `pass`, by photon index.
struct PhotonRadiiMessage {
  uint32_t pass = 0;
  std::vector<float> radii;
  static void fields(auto& self, auto&& visit) {
    auto& [pass, radii] = self;
    visit(pass, each(radii, CheckRadius{}));
  }
};

// Master to slave: the tiles of pass `pass` gather from the map this rank was sent as pass
// `keptPass` with keep set (the viewer's later views reuse their first view's pass-1 photons).
struct PhotonMapAgainMessage {
  uint32_t pass = 0;
  uint32_t keptPass = 0;
  PRISM_WIRE_FIELDS(pass, keptPass)
};

struct TileResultMessage {
  uint32_t frame = 0;
  TileResult result;  // result.pixels.size() == result.rect.pixelCount()
  // > 0: the pixels travel as the 8-bit display bytes this exposure gives (RenderView::
  // displayExposure), 3 bytes a pixel, and arrive as the smallest radiance that gives each byte
  // (DisplayEncoder::lowestRadianceOf): shown with the same exposure, they show the same.
  float displayExposure = 0.0f;
  static void fields(auto& self, auto&& visit) {
    auto& [frame, result, displayExposure] = self;
    auto& [tileIndex, rect, pixels, rays, seconds] = result;
    visit(frame, tileIndex, rect, tilePixels(result, displayExposure), rays, seconds);
  }
  static void check(const TileResultMessage& message);  // render time finite, not negative
};

struct ReadyMessage {
  double buildSeconds = 0;  // time the slave took to build its Scene
  int32_t threads = 0;      // threads it renders with
  // Its own start: from process start to its command (libraries, MPI; -1: not known), and
  // MPI_Init within that.
  double startSeconds = -1;
  double mpiInitSeconds = 0;
  PRISM_WIRE_FIELDS(buildSeconds, threads, startSeconds, mpiInitSeconds)
  static void check(const ReadyMessage& ready);  // times finite, not negative; threads ≥ 0
};

// Slave to master, before anything else: the instruction sets its CPU runs, so that rank 0 can
// choose one for the whole job (util/InstructionSet.h) before any rank renders a pixel.
struct HelloMessage {
  // An InstructionSetMask; the baseline's bit always set.
  uint32_t instructionSets = maskOf(InstructionSet::Baseline);
  std::string cpu;  // the CPU's model name, for messages about this rank
  PRISM_WIRE_FIELDS(instructionSets, cpu)
  static void check(const HelloMessage& hello);  // known sets, the baseline's among them; name
};

struct ErrorMessage {
  std::string text;
  PRISM_WIRE_FIELDS(text)
};

// Slave to master, once it has decoded the scene and checked it against its own memory (an
// Error says why not): rank 0 builds nothing before every slave has answered. What the slave
// builds with, for rank 0's choice between every rank building and broadcasting its build
// (master/dispatch/GeometryShare.h).
struct SceneAcceptedMessage {
  int32_t threads = 1;      // threads it builds and renders with
  int32_t cores = 1;        // its machine's cores
  int32_t ranksOnNode = 1;  // ranks of the job on its machine, itself included
  PRISM_WIRE_FIELDS(threads, cores, ranksOnNode)
  static void check(const SceneAcceptedMessage& accepted);  // each at least 1
};

// Master to every slave, broadcast once every slave has accepted the scene: build the geometry
// yourselves. Otherwise rank 0 broadcasts its own build (a Geometry message) in its place, or
// an Error when the job ends before anything is built. No payload.
struct BuildGeometryMessage {
  static void fields(auto&, auto&& visit) { visit(); }
};

// A slave's heartbeat while it has work: how many jobs it has received so far and which tiles
// it still holds (queued or rendering). Jobs and results travel in order between two ranks,
// so a tile sent among the first jobsReceived jobs that is neither held nor delivered was lost.
struct ProgressMessage {
  uint32_t frame = 0;  // the frame the counts belong to; they restart with each frame
  uint64_t jobsReceived = 0;
  std::vector<uint32_t> heldTiles;
  PRISM_WIRE_FIELDS(frame, jobsReceived, heldTiles)
};

// The viewer's render request: the TileJobs that follow with the same frame are tiles of this
// view. A View ends every frame before liveFrom, so a slave drops the jobs it still holds for
// them; frames from liveFrom on are still running (the viewer pipelines its frames).
struct ViewMessage {
  uint32_t frame = 0;
  uint32_t liveFrom = 0;  // ≤ frame; equal: this view ends every earlier frame
  RenderView view;
  PRISM_WIRE_FIELDS(frame, liveFrom, view)
  static void check(const ViewMessage& message);  // liveFrom ≤ frame
};

// Master to slave and back unchanged: a ping-pong that times the link (latency from small
// messages, bandwidth from tile-sized ones). The padding gives the message its size.
struct EchoMessage {
  uint32_t sequence = 0;
  std::string padding;
  PRISM_WIRE_FIELDS(sequence, padding)
};

// Master to slave: stop and answer with a Shutdown; slave to master: the answer. No payload.
struct ShutdownMessage {
  static void fields(auto&, auto&& visit) { visit(); }
};

// The message type of each struct in the list.
template <class T>
struct MessageTraits {};
#define PRISM_WIRE_TRAITS(name, number, Type, ...)          \
  template <>                                               \
  struct MessageTraits<Type> {                              \
    static constexpr MessageType kType = MessageType::name; \
  };
PRISM_WIRE_MESSAGES(PRISM_WIRE_TRAITS)
#undef PRISM_WIRE_TRAITS

template <class T>
concept WireMessage = requires {
  MessageTraits<T>::kType;
};

// The full message (envelope included) that carries value.
template <WireMessage T>
std::vector<uint8_t> encode(const T& value);

// The struct a message of T's type carries. Checks the type, every field and the struct, and
// that nothing is left over; throws WireError naming the message type.
template <WireMessage T>
T decode(const Message& message);

// A Scene message carries the scene description itself.
inline std::vector<uint8_t> encodeScene(const SceneDescription& scene) {
  return encode(scene);
}
inline SceneDescription decodeScene(const Message& message) {
  return decode<SceneDescription>(message);
}

// The same bytes as encode(PhotonMapMessage{...}) without first copying the photons into one.
std::vector<uint8_t> encodePhotonMap(uint32_t pass, const PhotonGatherSettings& gather,
                                     const std::vector<Photon>& photons, bool keep = false);

// Calls f(std::type_identity<T>{}) for the struct T of every message type, in the list's order.
template <class F>
void forEachMessageType(F&& f) {
#define PRISM_WIRE_EACH(name, number, Type, ...) f(std::type_identity<Type>{});
  PRISM_WIRE_MESSAGES(PRISM_WIRE_EACH)
#undef PRISM_WIRE_EACH
}

// T, named through F so that a use of it waits for visitMessage's instantiation: a struct only
// declared here (SceneGeometry) must be complete where a visitor is, not where this is defined.
template <class F, class T>
struct AsDependent {
  using type = T;
};

// Decodes message as the struct its type carries and returns f(that struct). A caller includes
// wire/GeometryCodec.h (the Geometry message's struct).
template <class F>
decltype(auto) visitMessage(const Message& message, F&& f) {
  switch (message.type) {
#define PRISM_WIRE_VISIT(name, number, Type, ...) \
  case MessageType::name:                         \
    return f(decode<typename AsDependent<F, Type>::type>(message));
    PRISM_WIRE_MESSAGES(PRISM_WIRE_VISIT)
#undef PRISM_WIRE_VISIT
  }
  throw WireError("unknown message type " + std::to_string(static_cast<int>(message.type)));
}

}  // namespace prism::wire

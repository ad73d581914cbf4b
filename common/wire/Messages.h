// The messages the master and the slaves exchange, as bytes. Each message is an envelope
// (magic, version, type, payload size, payload checksum) around a payload; decoding checks the
// envelope and then the payload strictly, and throws WireError naming what is wrong. No MPI
// here: the transport moves the bytes, this file gives them meaning.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "caustics/Photon.h"
#include "caustics/PhotonGatherSettings.h"
#include "caustics/PhotonTraceStats.h"
#include "render/RenderView.h"
#include "render/Tile.h"
#include "scene/SceneDescription.h"
#include "wire/ByteBuffer.h"

namespace prism::wire {

inline constexpr uint32_t kMagic = 0x4D535250;  // "PRSM" little-endian
// 2: TileJob carries the pass and its light terms; photon messages. 3: the View message.
// 4: PhotonJob carries the photon budget (the viewer changes it while the slaves run).
// 5: the caustic-map term of TileJob, the view's caustic-map blur switch, and the Echo
// message (`prism speedup` measures the links with it). 6: View names the oldest frame still
// running (pipelined frames) and says whether one sample per pixel is jittered. 7: PhotonCancel.
// 8: the automatic k (gather: auto) in the scene's caustics and the photon map's gather.
// 9: a View's display exposure, and TileResults as display bytes for frames only shown.
// 10: PhotonMap's keep flag and PhotonMapAgain (the viewer's later passes 1 reuse a kept map).
// 11: PhotonRadiiJob, PhotonRadiiShare and PhotonRadii (the ranks find a map's radii together).
inline constexpr uint16_t kVersion = 11;
// magic u32, version u16, type u16, payload size u64, FNV-1a 64 checksum of the payload u64.
inline constexpr size_t kHeaderSize = 24;

enum class MessageType : uint16_t {
  Scene = 1,
  Ready = 2,
  TileJob = 3,
  TileResult = 4,
  Shutdown = 5,
  Error = 6,
  Progress = 7,
  PhotonJob = 8,
  PhotonShare = 9,
  PhotonMap = 10,
  View = 11,
  Echo = 12,
  PhotonCancel = 13,
  PhotonMapAgain = 14,
  PhotonRadiiJob = 15,
  PhotonRadiiShare = 16,
  PhotonRadii = 17
};

// "Scene", "TileResult", ...; "unknown" for values outside the enumeration.
const char* messageTypeName(MessageType type);

// FNV-1a, 64 bit: detects every single-byte change, which is what a checksum here is for.
uint64_t fnv1a64(const uint8_t* data, size_t size);

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
};

// Master to slave: trace photons [first, first + count) of a pass and send them back.
// photonsPerPass is the budget the master's tracer was planned with: photon powers and the
// split between lights depend on it, so the slave plans its tracer with the same budget.
struct PhotonJobMessage {
  uint32_t pass = 0;
  uint64_t first = 0;
  uint64_t count = 0;
  uint64_t photonsPerPass = 0;
};

// Master to slave: stop the PhotonJob or PhotonRadiiJob of this pass and send nothing for it
// (the camera moved or the viewer stopped: rank 0 dropped the pass).
struct PhotonCancelMessage {
  uint32_t pass = 0;
};

// Slave to master: the photons it stored for a PhotonJob, in photon-index order.
struct PhotonShareMessage {
  uint32_t pass = 0;
  uint64_t first = 0;
  uint64_t count = 0;
  PhotonTraceStats stats;
  double seconds = 0;
  std::vector<Photon> photons;
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
};

// Master to slave: find the radii of positions [first, first + count) of the spatial order of
// the map of `pass` (caustics/PhotonRadii.h) and send them back.
struct PhotonRadiiJobMessage {
  uint32_t pass = 0;
  uint64_t first = 0;
  uint64_t count = 0;
};

// Slave to master: the radii of a PhotonRadiiJob, in spatial order from `first`.
struct PhotonRadiiShareMessage {
  uint32_t pass = 0;
  uint64_t first = 0;
  std::vector<float> radii;
};

// Master to slave: every photon's radius of the map of `pass`, by photon index.
struct PhotonRadiiMessage {
  uint32_t pass = 0;
  std::vector<float> radii;
};

// Master to slave: the tiles of pass `pass` gather from the map this rank was sent as pass
// `keptPass` with keep set (the viewer's later views reuse their first view's pass-1 photons).
struct PhotonMapAgainMessage {
  uint32_t pass = 0;
  uint32_t keptPass = 0;
};

struct TileResultMessage {
  uint32_t frame = 0;
  TileResult result;  // result.pixels.size() == result.rect.pixelCount()
  // > 0: the pixels travel as the 8-bit display bytes this exposure gives (RenderView::
  // displayExposure), 3 bytes a pixel, and arrive as the smallest radiance that gives each byte
  // (DisplayEncoder::lowestRadianceOf): shown with the same exposure, they show the same.
  float displayExposure = 0.0f;
};

struct ReadyMessage {
  double buildSeconds = 0;  // time the slave took to build its Scene
  int32_t threads = 0;      // threads it renders with
  // Its own start: from process start to its command (libraries, MPI; -1: not known), and
  // MPI_Init within that.
  double startSeconds = -1;
  double mpiInitSeconds = 0;
};

struct ErrorMessage {
  std::string text;
};

// A slave's heartbeat while it has work: how many jobs it has received so far and which tiles
// it still holds (queued or rendering). Jobs and results travel in order between two ranks,
// so a tile sent among the first jobsReceived jobs that is neither held nor delivered was lost.
struct ProgressMessage {
  uint32_t frame = 0;  // the frame the counts belong to; they restart with each frame
  uint64_t jobsReceived = 0;
  std::vector<uint32_t> heldTiles;
};

// The viewer's render request: the TileJobs that follow with the same frame are tiles of this
// view. A View ends every frame before liveFrom, so a slave drops the jobs it still holds for
// them; frames from liveFrom on are still running (the viewer pipelines its frames).
struct ViewMessage {
  uint32_t frame = 0;
  uint32_t liveFrom = 0;  // ≤ frame; equal: this view ends every earlier frame
  RenderView view;
};

// Master to slave and back unchanged: a ping-pong that times the link (latency from small
// messages, bandwidth from tile-sized ones). The padding gives the message its size.
struct EchoMessage {
  uint32_t sequence = 0;
  std::string padding;
};

// Each encodeX returns a full message (envelope included); each decodeX checks the message type
// and the payload (sizes, ranges, nothing left over) and throws WireError.
std::vector<uint8_t> encodeScene(const SceneDescription& scene);
SceneDescription decodeScene(const Message& message);

std::vector<uint8_t> encodeTileJob(const TileJobMessage& job);
TileJobMessage decodeTileJob(const Message& message);

std::vector<uint8_t> encodeTileResult(const TileResultMessage& result);
TileResultMessage decodeTileResult(const Message& message);

std::vector<uint8_t> encodeReady(const ReadyMessage& ready);
ReadyMessage decodeReady(const Message& message);

std::vector<uint8_t> encodeError(const ErrorMessage& error);
ErrorMessage decodeError(const Message& message);

std::vector<uint8_t> encodeProgress(const ProgressMessage& progress);
ProgressMessage decodeProgress(const Message& message);

std::vector<uint8_t> encodeView(const ViewMessage& view);
ViewMessage decodeView(const Message& message);
std::vector<uint8_t> encodePhotonJob(const PhotonJobMessage& job);
PhotonJobMessage decodePhotonJob(const Message& message);

std::vector<uint8_t> encodePhotonCancel(const PhotonCancelMessage& cancel);
PhotonCancelMessage decodePhotonCancel(const Message& message);

std::vector<uint8_t> encodePhotonShare(const PhotonShareMessage& share);
PhotonShareMessage decodePhotonShare(const Message& message);

std::vector<uint8_t> encodePhotonMap(const PhotonMapMessage& map);
// The same bytes without first copying the photons into a message struct.
std::vector<uint8_t> encodePhotonMap(uint32_t pass, const PhotonGatherSettings& gather,
                                     const std::vector<Photon>& photons, bool keep = false);
PhotonMapMessage decodePhotonMap(const Message& message);

std::vector<uint8_t> encodePhotonRadiiJob(const PhotonRadiiJobMessage& job);
PhotonRadiiJobMessage decodePhotonRadiiJob(const Message& message);

std::vector<uint8_t> encodePhotonRadiiShare(const PhotonRadiiShareMessage& share);
PhotonRadiiShareMessage decodePhotonRadiiShare(const Message& message);

std::vector<uint8_t> encodePhotonRadii(const PhotonRadiiMessage& radii);
PhotonRadiiMessage decodePhotonRadii(const Message& message);

std::vector<uint8_t> encodePhotonMapAgain(const PhotonMapAgainMessage& again);
PhotonMapAgainMessage decodePhotonMapAgain(const Message& message);

std::vector<uint8_t> encodeEcho(const EchoMessage& echo);
EchoMessage decodeEcho(const Message& message);

std::vector<uint8_t> encodeShutdown();
// Checks that message is a Shutdown with an empty payload.
void decodeShutdown(const Message& message);

}  // namespace prism::wire

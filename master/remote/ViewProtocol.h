// The messages between a job serving its live session (ViewServer) and a viewer connected to it
// (ViewClient), as bytes on a TCP stream. Each message is an envelope like the cluster's
// (wire/Messages.h) with a magic of its own ("PRSV": a cluster message sent here, or this sent
// to a rank, is refused at once), a protocol version, the type, the payload size and an FNV-1a
// checksum; News and FullImage payloads are zstd-compressed (zstd level 1: measured in
// docs/viewer.md). The reader checks the header (magic, version, known type, size under the
// limit of its direction) before it reads a byte of the payload, and the decompressed size
// before it allocates. Fields are described once (wire/Fields.h), so encode and decode follow.
//
// A viewer's first message is Hello with the job's token; the job reads nothing else before it
// has checked it. PRISM_VIEW_MESSAGES is the one list of message types.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "master/live/DisplayNews.h"
#include "master/live/LiveSource.h"
#include "wire/ByteBuffer.h"
#include "wire/Fields.h"

namespace prism::view {

inline constexpr uint32_t kMagic = 0x56535250;  // "PRSV" little-endian
// 2: ViewerStart names the ray kernels' instruction set.
inline constexpr uint16_t kVersion = 3;
// magic u32, version u16, type u16, payload size u64, FNV-1a 64 checksum of the payload u64.
inline constexpr size_t kHeaderSize = 24;

// Client to server: Hello (first, with the token), SetView, FullImageRequest, Ping, Bye,
// NewsReceived.
// Server to client: Welcome or Refused (the answer to Hello), News, FullImage, JobEnded.
struct HelloMessage {
  std::string token;
  std::string client;  // "prism connect on HOST", for the job's log
  PRISM_WIRE_FIELDS(token, client)
};
struct WelcomeMessage {
  ViewerStart start;
  PRISM_WIRE_FIELDS(start)
};
struct RefusedMessage {
  std::string reason;
  PRISM_WIRE_FIELDS(reason)
};
struct FullImageRequestMessage {
  uint32_t request = 0;
  PRISM_WIRE_FIELDS(request)
};
struct FullImageMessage {
  uint32_t request = 0;
  ImageRgb image;  // linear radiance of what is on show
  PRISM_WIRE_FIELDS(request, image)
};
struct PingMessage {
  static void fields(auto&, auto&& visit) { visit(); }
};
struct ByeMessage {
  static void fields(auto&, auto&& visit) { visit(); }
};
struct JobEndedMessage {
  std::string reason;
  PRISM_WIRE_FIELDS(reason)
};
// The viewer has received this many News messages in all. The job sends the next news only
// while fewer than two are unacknowledged, so news waits merged on the job's board rather than
// in buffers along a slow link: what arrives is the newest picture.
struct NewsReceivedMessage {
  uint64_t count = 0;
  PRISM_WIRE_FIELDS(count)
};

#define PRISM_VIEW_MESSAGES(X)                           \
  X(Hello, 1, HelloMessage, false)                       \
  X(Welcome, 2, WelcomeMessage, false)                   \
  X(Refused, 3, RefusedMessage, false)                   \
  X(SetView, 4, ViewSettings, false)                     \
  X(News, 5, DisplayNews, true)                          \
  X(FullImageRequest, 6, FullImageRequestMessage, false) \
  X(FullImage, 7, FullImageMessage, true)                \
  X(Ping, 8, PingMessage, false)                         \
  X(Bye, 9, ByeMessage, false)                           \
  X(JobEnded, 10, JobEndedMessage, false)                \
  X(NewsReceived, 11, NewsReceivedMessage, false)

enum class MessageType : uint16_t {
#define PRISM_VIEW_ENUMERATOR(name, number, Type, compressed) name = number,
  PRISM_VIEW_MESSAGES(PRISM_VIEW_ENUMERATOR)
#undef PRISM_VIEW_ENUMERATOR
};

const char* messageTypeName(MessageType type);  // "unknown" outside the list
bool isKnownType(uint16_t raw);

// What a reader accepts: payload bytes on the wire, and (for compressed types) decompressed.
struct Limits {
  size_t maxPayload;
  size_t maxUnpacked;
};
// A server reads small messages only; a client reads frames (display bytes, or an EXR's floats
// of a frame up to 16384 × 16384).
inline constexpr Limits kClientToServer{64 * 1024, 64 * 1024};
inline constexpr Limits kServerToClient{size_t{4} << 30, size_t{4} << 30};

// The envelope's header, checked: magic, version, known type, size within limits. Throws
// WireError; VersionMismatch for a message of another protocol version.
class VersionMismatch : public wire::WireError {
 public:
  explicit VersionMismatch(uint16_t version);
  uint16_t version;
};
struct Header {
  MessageType type;
  uint64_t size = 0;
  uint64_t checksum = 0;
};
Header readHeader(const uint8_t* header, const Limits& limits);

// A message whose envelope checked out: its type and its payload, decompressed.
struct Message {
  MessageType type;
  std::vector<uint8_t> payload;
};
// Checks the payload's checksum and decompresses it. Throws WireError.
Message openPayload(const Header& header, const uint8_t* payload, const Limits& limits);
// Header and payload together (a whole message in one buffer, nothing left over).
Message decodeMessage(const uint8_t* data, size_t size, const Limits& limits);

template <class T>
struct MessageTraits {};
#define PRISM_VIEW_TRAITS(name, number, Type, isCompressed) \
  template <>                                               \
  struct MessageTraits<Type> {                              \
    static constexpr MessageType kType = MessageType::name; \
    static constexpr bool kCompressed = isCompressed;       \
  };
PRISM_VIEW_MESSAGES(PRISM_VIEW_TRAITS)
#undef PRISM_VIEW_TRAITS

template <class T>
concept ViewMessage = requires {
  MessageTraits<T>::kType;
};

// The whole message (envelope included) around a payload of encoded fields, compressed when the
// type's messages are (fuzzing and tests build messages of any content with it).
std::vector<uint8_t> encodePayload(MessageType type, std::vector<uint8_t> fields);

// The whole message (envelope included) that carries value.
template <ViewMessage T>
std::vector<uint8_t> encode(const T& value);
// The struct a message of T's type carries; checks every field and that nothing is left over.
template <ViewMessage T>
T decode(const Message& message);

// Calls f(std::type_identity<T>{}) for each message type's struct, in the list's order.
template <class F>
void forEachMessageType(F&& f) {
#define PRISM_VIEW_EACH(name, number, Type, compressed) f(std::type_identity<Type>{});
  PRISM_VIEW_MESSAGES(PRISM_VIEW_EACH)
#undef PRISM_VIEW_EACH
}

}  // namespace prism::view

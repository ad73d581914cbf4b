#include "fuzz/Harnesses.h"
#include "wire/Messages.h"

namespace prism::fuzz {

namespace {

using namespace prism::wire;

// A decoded message must encode to the very bytes it came from: the format has one encoding
// per value, so a difference means a decoder accepted something it should have refused (or
// dropped data).
template <typename Decoded>
void expectSameBytes(const std::vector<uint8_t>& original, const Decoded& decoded,
                     std::vector<uint8_t> (*encode)(const Decoded&)) {
  if (encode(decoded) != original) {
    throw InvariantBroken("decoded message does not encode back to the same bytes");
  }
}

void decodePayload(const std::vector<uint8_t>& bytes) {
  const Message message = decodeMessage(bytes);
  switch (message.type) {
    case MessageType::Scene:
      expectSameBytes(bytes, decodeScene(message), &encodeScene);
      break;
    case MessageType::Ready:
      expectSameBytes(bytes, decodeReady(message), &encodeReady);
      break;
    case MessageType::TileJob:
      expectSameBytes(bytes, decodeTileJob(message), &encodeTileJob);
      break;
    case MessageType::TileResult:
      expectSameBytes(bytes, decodeTileResult(message), &encodeTileResult);
      break;
    case MessageType::Shutdown:
      decodeShutdown(message);
      if (encodeShutdown() != bytes) throw InvariantBroken("Shutdown with a payload accepted");
      break;
    case MessageType::Error:
      expectSameBytes(bytes, decodeError(message), &encodeError);
      break;
    case MessageType::Progress:
      expectSameBytes(bytes, decodeProgress(message), &encodeProgress);
      break;
    case MessageType::PhotonJob:
      expectSameBytes(bytes, decodePhotonJob(message), &encodePhotonJob);
      break;
    case MessageType::PhotonShare:
      expectSameBytes(bytes, decodePhotonShare(message), &encodePhotonShare);
      break;
    case MessageType::PhotonMap: {
      std::vector<uint8_t> (*encode)(const PhotonMapMessage&) = &encodePhotonMap;
      expectSameBytes(bytes, decodePhotonMap(message), encode);
      break;
    }
    case MessageType::View:
      expectSameBytes(bytes, decodeView(message), &encodeView);
      break;
    case MessageType::Echo:
      expectSameBytes(bytes, decodeEcho(message), &encodeEcho);
      break;
    case MessageType::PhotonCancel:
      expectSameBytes(bytes, decodePhotonCancel(message), &encodePhotonCancel);
      break;
    case MessageType::PhotonMapAgain:
      expectSameBytes(bytes, decodePhotonMapAgain(message), &encodePhotonMapAgain);
      break;
    case MessageType::PhotonRadiiJob:
      expectSameBytes(bytes, decodePhotonRadiiJob(message), &encodePhotonRadiiJob);
      break;
    case MessageType::PhotonRadiiShare:
      expectSameBytes(bytes, decodePhotonRadiiShare(message), &encodePhotonRadiiShare);
      break;
    case MessageType::PhotonRadii:
      expectSameBytes(bytes, decodePhotonRadii(message), &encodePhotonRadii);
      break;
    default:
      throw InvariantBroken("decodeMessage accepted an unknown message type");
  }
}

}  // namespace

Outcome fuzzWire(const uint8_t* data, size_t size) {
  bool accepted = false;
  try {
    const Message message = decodeMessage(data, size);
    if (encodeMessage(message.type, message.payload) != std::vector<uint8_t>(data, data + size)) {
      throw InvariantBroken("envelope does not encode back to the same bytes");
    }
    accepted = true;
  } catch (const WireError&) {
  }
  if (size == 0) return accepted ? Outcome::Accepted : Outcome::Rejected;
  // Types 1..13 are known; the rest of the byte's range checks that unknown types are refused.
  const auto type = static_cast<MessageType>(data[0] % 16);
  try {
    decodePayload(encodeMessage(type, std::vector<uint8_t>(data + 1, data + size)));
    accepted = true;
  } catch (const WireError&) {
  }
  return accepted ? Outcome::Accepted : Outcome::Rejected;
}

}  // namespace prism::fuzz

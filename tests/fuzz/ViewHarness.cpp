#include <cstdint>

#include "fuzz/Harnesses.h"
#include "master/remote/ViewProtocol.h"

namespace prism::fuzz {
namespace {

using namespace prism::view;

// Small enough that a mutated size field cannot make the harness allocate much.
constexpr Limits kFuzzLimits{1 << 20, 4 << 20};

// Decodes message as the struct its type carries; a decoded value must encode back to
// `canonical` when given (one encoding per value, so a difference is a decoder that accepted
// what it should have refused).
void decodeTyped(const Message& message, const std::vector<uint8_t>* canonical) {
  bool known = false;
  forEachMessageType([&](auto type) {
    using T = typename decltype(type)::type;
    if (MessageTraits<T>::kType != message.type) return;
    known = true;
    const T value = decode<T>(message);
    if (canonical && encode(value) != *canonical) {
      throw InvariantBroken("decoded view message does not encode back to the same bytes");
    }
  });
  if (!known) throw InvariantBroken("decodeMessage accepted an unknown view message type");
}

}  // namespace

Outcome fuzzView(const uint8_t* data, size_t size) {
  bool accepted = false;
  try {  // the bytes as a whole message
    decodeTyped(decodeMessage(data, size, kFuzzLimits), nullptr);
    accepted = true;
  } catch (const wire::WireError&) {
  }
  if (size == 0) return accepted ? Outcome::Accepted : Outcome::Rejected;
  // The bytes after the first as the fields of a message of the type the first byte chooses
  // (0 and 12..15 are unknown and must be refused), in a valid envelope (compressed where the
  // type is), so that mutations reach the field decoders past the checksum.
  const auto type = static_cast<MessageType>(data[0] % 16);
  try {
    const std::vector<uint8_t> bytes =
        encodePayload(type, std::vector<uint8_t>(data + 1, data + size));
    decodeTyped(decodeMessage(bytes.data(), bytes.size(), kFuzzLimits), &bytes);
    accepted = true;
  } catch (const wire::WireError&) {
  }
  return accepted ? Outcome::Accepted : Outcome::Rejected;
}

}  // namespace prism::fuzz

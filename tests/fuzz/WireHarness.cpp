#include <cstdint>
#include <type_traits>

#include "fuzz/Harnesses.h"
#include "wire/GeometryCodec.h"
#include "wire/Messages.h"

namespace prism::fuzz {

namespace {

using namespace prism::wire;

// The type byte of the harness's second form is taken modulo the smallest power of two above the
// largest type number: every known type is reached, and so are unknown ones (0 and those past the
// largest), which must be refused.
constexpr int typeByteRange() {
  int largest = 0;
  for (int raw = 0; raw <= UINT16_MAX; ++raw) {
    if (isKnownType(static_cast<uint16_t>(raw))) largest = raw;
  }
  int range = 1;
  while (range <= largest) range *= 2;
  return range;
}

// A decoded message must encode to the very bytes it came from: the format has one encoding
// per value, so a difference means a decoder accepted something it should have refused (or
// dropped data).
void decodePayload(const std::vector<uint8_t>& bytes) {
  const Message message = decodeMessage(bytes);
  if (!isKnownType(static_cast<uint16_t>(message.type))) {
    throw InvariantBroken("decodeMessage accepted an unknown message type");
  }
  visitMessage(message, [&](const auto& decoded) {
    if (encode(decoded) != bytes) {
      throw InvariantBroken("decoded message does not encode back to the same bytes");
    }
    // A geometry that passed its checks must walk without reading outside its arrays (the
    // sanitizers see to that) or looping: a few rays from around its box, each walk and lookup.
    if constexpr (std::is_same_v<std::decay_t<decltype(decoded)>, SceneGeometry>) {
      const Aabb box = decoded.bounds();
      const Vec3 center = box.empty() ? Vec3(0.0f) : box.center();
      for (const Vec3& from :
           {Vec3(0.0f, 0.0f, -50.0f), Vec3(30.0f, 40.0f, 0.0f), Vec3(-20.0f, -10.0f, 35.0f)}) {
        Ray ray;
        ray.origin = center + from;
        ray.direction = glm::normalize(-from);
        HitRecord hit;
        if (decoded.intersect(ray, hit)) {
          SurfaceHit surface;
          decoded.surface(ray, hit, surface);
        }
        decoded.occluded(ray);
        Ray rays[SceneGeometry::kPacketSize];
        for (Ray& r : rays) r = ray;
        HitRecord hits[SceneGeometry::kPacketSize];
        bool found[SceneGeometry::kPacketSize];
        decoded.intersect8(rays, SceneGeometry::kPacketSize, hits, found);
      }
    }
  });
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
  static constexpr int kTypeByteRange = typeByteRange();
  const auto type = static_cast<MessageType>(data[0] % kTypeByteRange);
  try {
    decodePayload(encodeMessage(type, std::vector<uint8_t>(data + 1, data + size)));
    accepted = true;
  } catch (const WireError&) {
  }
  return accepted ? Outcome::Accepted : Outcome::Rejected;
}

}  // namespace prism::fuzz

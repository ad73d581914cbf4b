#include "master/remote/ViewProtocol.h"

#include <gtest/gtest.h>

#include "fuzz/ViewExamples.h"
#include "master/remote/ViewFields.h"
#include "wire/FieldCodec.h"

namespace prism {
namespace {

using namespace prism::view;

Message decodeAll(const std::vector<uint8_t>& bytes, const Limits& limits = kServerToClient) {
  return decodeMessage(bytes.data(), bytes.size(), limits);
}

std::string errorOf(const std::vector<uint8_t>& bytes, const Limits& limits = kServerToClient) {
  try {
    decodeAll(bytes, limits);
  } catch (const wire::WireError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ViewProtocol, EveryMessageRoundTrips) {
  int types = 0;
  forEachMessageType([&](auto) { ++types; });
  const auto examples = fuzz::viewExamples();
  ASSERT_EQ(static_cast<int>(examples.size()), types) << "an example per message type";
  for (const auto& example : examples) {
    SCOPED_TRACE(example.first);
    const auto& bytes = example.second;  // not a structured binding: clang-14 cannot capture one
    const Message message = decodeAll(bytes);
    forEachMessageType([&](auto type) {
      using T = typename decltype(type)::type;
      if (MessageTraits<T>::kType != message.type) return;
      EXPECT_EQ(encode(decode<T>(message)), bytes);
    });
  }
  const DisplayNews news = fuzz::exampleNews();
  EXPECT_TRUE(wire::sameFields(decode<DisplayNews>(decodeAll(encode(news))), news));
}

TEST(ViewProtocol, NewsIsCompressed) {
  DisplayNews news = fuzz::exampleNews();
  news.width = 640;
  news.height = 360;
  news.patch = {0, 0, 640, 360};
  news.patchBytes.assign(640 * 360 * 3, 40);  // a flat frame: compresses to almost nothing
  const std::vector<uint8_t> bytes = encode(news);
  EXPECT_LT(bytes.size(), news.patchBytes.size() / 100);
  EXPECT_EQ(decode<DisplayNews>(decodeAll(bytes)).patchBytes, news.patchBytes);
}

TEST(ViewProtocol, TheHeaderIsCheckedBeforeThePayload) {
  std::vector<uint8_t> hello = fuzz::viewExamples().front().second;
  // Another protocol version: its own error, which names both versions.
  std::vector<uint8_t> newer = hello;
  newer[4] = static_cast<uint8_t>(kVersion + 1);
  try {
    decodeAll(newer);
    FAIL() << "a newer version was accepted";
  } catch (const VersionMismatch& e) {
    EXPECT_EQ(e.version, kVersion + 1);
    EXPECT_EQ(std::string(e.what()), "protocol version " + std::to_string(kVersion + 1) +
                                         ", this Prism speaks version " + std::to_string(kVersion) +
                                         ": use the same Prism release on both sides");
  }
  // A cluster message, or anything else.
  std::vector<uint8_t> other = hello;
  other[3] = 'M';
  EXPECT_EQ(errorOf(other), "not a Prism viewer message (it does not start with PRSV)");
  std::vector<uint8_t> unknown = hello;
  unknown[6] = 42;
  EXPECT_EQ(errorOf(unknown), "unknown message type 42");
  // An oversized length is refused from the header alone, before a byte of payload is read.
  std::vector<uint8_t> header(hello.begin(), hello.begin() + kHeaderSize);
  header[8 + 7] = 0x40;  // 2^62 bytes
  EXPECT_EQ(errorOf(header, kClientToServer).rfind("Hello of 4611686018427387", 0), 0u)
      << errorOf(header, kClientToServer);
  EXPECT_THROW(readHeader(header.data(), kClientToServer), wire::WireError);
  // A changed payload byte.
  std::vector<uint8_t> changed = hello;
  changed.back() ^= 1;
  EXPECT_EQ(errorOf(changed), "Hello: payload checksum mismatch");
}

TEST(ViewProtocol, ACompressedPayloadIsBoundedBeforeItIsUnpacked) {
  DisplayNews news = fuzz::exampleNews();
  news.width = 1024;
  news.height = 1024;
  news.patch = {0, 0, 1024, 1024};
  news.patchBytes.assign(size_t{1024} * 1024 * 3, 7);
  const std::vector<uint8_t> bytes = encode(news);
  EXPECT_EQ(errorOf(bytes, Limits{1 << 20, 1 << 20}).find("payload unpacks to "), 0u);
  // Not zstd at all, behind a valid checksum.
  std::vector<uint8_t> notZstd = encode(RefusedMessage{"x"});
  notZstd[6] = static_cast<uint8_t>(MessageType::News);
  const uint64_t checksum =
      wire::fnv1a64(notZstd.data() + kHeaderSize, notZstd.size() - kHeaderSize);
  for (int i = 0; i < 8; ++i) notZstd[16 + i] = static_cast<uint8_t>(checksum >> (8 * i));
  EXPECT_EQ(errorOf(notZstd), "payload is not a zstd frame");
}

TEST(ViewProtocol, NewsWhosePatchLeavesTheFrameIsRefused) {
  DisplayNews news = fuzz::exampleNews();
  news.patch = {6, 0, 3, 2};  // 6 + 3 > 8
  const std::string error = [&] {
    try {
      decode<DisplayNews>(decodeAll(encode(news)));
    } catch (const wire::WireError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  }();
  EXPECT_EQ(error, "News: patch 3x2+6+0 outside the 8x4 frame");
  news = fuzz::exampleNews();
  news.patchBytes.pop_back();
  EXPECT_THROW(decode<DisplayNews>(decodeAll(encode(news))), wire::WireError);
}

}  // namespace
}  // namespace prism

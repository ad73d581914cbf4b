#include "wire/Messages.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <functional>
#include <limits>

namespace prism::wire {
namespace {

TileResultMessage sampleTileResult() {
  TileResultMessage m;
  m.frame = 7;
  m.result.tileIndex = 42;
  m.result.rect = {64, 32, 3, 2};
  for (int i = 0; i < 6; ++i) {
    m.result.pixels.push_back(Color(0.1f * i, -0.0f, std::numeric_limits<float>::infinity()));
  }
  m.result.pixels[5] = Color(std::bit_cast<float>(0x7FC00001u), 1e-40f, 3.0f);
  m.result.rays = {6, 12, 0x1234567890ull};
  m.result.seconds = 0.015625;
  return m;
}

// Builds a message whose envelope is valid around a hand-made payload, so only the payload
// checks can reject it.
template <typename WritePayload>
Message handMade(MessageType type, WritePayload writePayload) {
  ByteWriter w;
  writePayload(w);
  return decodeMessage(encodeMessage(type, w.bytes()));
}

void expectWireError(const std::function<void()>& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no WireError; expected one containing \"" << fragment << "\"";
  } catch (const WireError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

std::vector<uint8_t> header(uint32_t magic, uint16_t version, uint16_t type, uint64_t size,
                            uint64_t checksum) {
  ByteWriter w;
  w.writeU32(magic);
  w.writeU16(version);
  w.writeU16(type);
  w.writeU64(size);
  w.writeU64(checksum);
  return w.take();
}

TEST(Messages, Fnv1aMatchesTheReferenceValues) {
  const uint8_t a[] = {'a'};
  const uint8_t foobar[] = {'f', 'o', 'o', 'b', 'a', 'r'};
  EXPECT_EQ(fnv1a64(nullptr, 0), 0xCBF29CE484222325ull);
  EXPECT_EQ(fnv1a64(a, 1), 0xAF63DC4C8601EC8Cull);
  EXPECT_EQ(fnv1a64(foobar, 6), 0x85944171F73967E8ull);
}

TEST(Messages, EnvelopeLayout) {
  const std::vector<uint8_t> payload = {'a'};
  const std::vector<uint8_t> bytes = encodeMessage(MessageType::Error, payload);
  ASSERT_EQ(bytes.size(), kHeaderSize + 1);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 4), "PRSM");
  EXPECT_EQ(std::vector<uint8_t>(bytes.begin(), bytes.begin() + kHeaderSize),
            header(kMagic, 1, 6, 1, 0xAF63DC4C8601EC8Cull));
  EXPECT_EQ(bytes.back(), 'a');
}

TEST(Messages, TypeNames) {
  EXPECT_STREQ(messageTypeName(MessageType::Scene), "Scene");
  EXPECT_STREQ(messageTypeName(MessageType::Ready), "Ready");
  EXPECT_STREQ(messageTypeName(MessageType::TileJob), "TileJob");
  EXPECT_STREQ(messageTypeName(MessageType::TileResult), "TileResult");
  EXPECT_STREQ(messageTypeName(MessageType::Shutdown), "Shutdown");
  EXPECT_STREQ(messageTypeName(MessageType::Error), "Error");
  EXPECT_STREQ(messageTypeName(static_cast<MessageType>(99)), "unknown");
}

TEST(Messages, TileJobRoundTrips) {
  const TileJobMessage job{3, 17, {128, 64, 32, 16}};
  const Message m = decodeMessage(encodeTileJob(job));
  EXPECT_EQ(m.type, MessageType::TileJob);
  const TileJobMessage back = decodeTileJob(m);
  EXPECT_EQ(back.frame, 3u);
  EXPECT_EQ(back.tileIndex, 17u);
  EXPECT_EQ(back.rect.x, 128);
  EXPECT_EQ(back.rect.y, 64);
  EXPECT_EQ(back.rect.width, 32);
  EXPECT_EQ(back.rect.height, 16);
}

TEST(Messages, TileResultRoundTripsBitExact) {
  const TileResultMessage sent = sampleTileResult();
  const TileResultMessage back = decodeTileResult(decodeMessage(encodeTileResult(sent)));
  EXPECT_EQ(back.frame, sent.frame);
  EXPECT_EQ(back.result.tileIndex, sent.result.tileIndex);
  EXPECT_EQ(back.result.rect.x, sent.result.rect.x);
  EXPECT_EQ(back.result.rect.y, sent.result.rect.y);
  EXPECT_EQ(back.result.rect.width, sent.result.rect.width);
  EXPECT_EQ(back.result.rect.height, sent.result.rect.height);
  ASSERT_EQ(back.result.pixels.size(), sent.result.pixels.size());
  for (size_t i = 0; i < sent.result.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(std::bit_cast<uint32_t>(back.result.pixels[i][c]),
                std::bit_cast<uint32_t>(sent.result.pixels[i][c]))
          << "pixel " << i << " channel " << c;
    }
  }
  EXPECT_EQ(back.result.rays.primary, sent.result.rays.primary);
  EXPECT_EQ(back.result.rays.shadow, sent.result.rays.shadow);
  EXPECT_EQ(back.result.rays.secondary, sent.result.rays.secondary);
  EXPECT_EQ(back.result.seconds, sent.result.seconds);
}

TEST(Messages, ReadyErrorAndShutdownRoundTrip) {
  const ReadyMessage ready = decodeReady(decodeMessage(encodeReady({1.25, 16})));
  EXPECT_EQ(ready.buildSeconds, 1.25);
  EXPECT_EQ(ready.threads, 16);

  const std::string text = "scene.yaml:3:7: unknown material 'glas'\n\ttab and \xC3\xA9";
  EXPECT_EQ(decodeError(decodeMessage(encodeError({text}))).text, text);
  EXPECT_EQ(decodeError(decodeMessage(encodeError({""}))).text, "");

  const std::vector<uint8_t> shutdown = encodeShutdown();
  EXPECT_EQ(shutdown.size(), kHeaderSize);
  const Message m = decodeMessage(shutdown);
  EXPECT_EQ(m.type, MessageType::Shutdown);
  EXPECT_TRUE(m.payload.empty());
  EXPECT_NO_THROW(decodeShutdown(m));
}

TEST(Messages, EnvelopeErrorsSayWhatIsWrong) {
  const std::vector<uint8_t> good = encodeError({"x"});
  expectWireError([&] { decodeMessage(good.data(), 10); },
                  "message too short for a header: 10 bytes, a header needs 24");

  std::vector<uint8_t> bad = good;
  bad[0] = 'Q';
  expectWireError([&] { decodeMessage(bad); }, "bad magic 0x4D535251");

  bad = header(kMagic, 2, 6, 0, fnv1a64(nullptr, 0));
  expectWireError([&] { decodeMessage(bad); }, "message version 2, this build speaks 1");

  for (uint16_t type : {0, 8, 0xFFFF}) {
    bad = header(kMagic, 1, type, 0, fnv1a64(nullptr, 0));
    expectWireError([&] { decodeMessage(bad); }, "unknown message type " + std::to_string(type));
  }

  bad = good;
  bad.push_back(0);
  expectWireError([&] { decodeMessage(bad); },
                  "payload size mismatch: header declares 5 bytes, message carries 6");

  bad = good;
  bad.back() ^= 1;
  expectWireError([&] { decodeMessage(bad); }, "payload checksum mismatch");
}

TEST(Messages, DecodersRejectTheWrongMessageType) {
  const Message ready = decodeMessage(encodeReady({0.5, 2}));
  expectWireError([&] { decodeTileJob(ready); }, "expected a TileJob message, got Ready");
  expectWireError([&] { decodeTileResult(ready); }, "expected a TileResult message, got Ready");
  expectWireError([&] { decodeError(ready); }, "expected a Error message, got Ready");
  expectWireError([&] { decodeScene(ready); }, "expected a Scene message, got Ready");
  expectWireError([&] { decodeShutdown(ready); }, "expected a Shutdown message, got Ready");
  const Message shutdown = decodeMessage(encodeShutdown());
  expectWireError([&] { decodeReady(shutdown); }, "expected a Ready message, got Shutdown");
}

TEST(Messages, EverySingleByteCorruptionOfATileResultIsRejected) {
  const std::vector<uint8_t> good = encodeTileResult(sampleTileResult());
  ASSERT_NO_THROW(decodeTileResult(decodeMessage(good)));
  for (size_t i = 0; i < good.size(); ++i) {
    for (int mask : {0x01, 0x02, 0x04, 0x08, 0x10, 0x20, 0x40, 0x80, 0xFF}) {
      std::vector<uint8_t> bad = good;
      bad[i] ^= static_cast<uint8_t>(mask);
      EXPECT_THROW(decodeTileResult(decodeMessage(bad)), WireError)
          << "byte " << i << " xor " << mask;
    }
  }
}

TEST(Messages, EveryTruncationOfATileResultIsRejected) {
  const std::vector<uint8_t> good = encodeTileResult(sampleTileResult());
  for (size_t length = 0; length < good.size(); ++length) {
    EXPECT_THROW(decodeTileResult(decodeMessage(good.data(), length)), WireError) << length;
  }
}

TEST(Messages, TileResultPixelCountMustMatchTheRectangle) {
  TileResultMessage m = sampleTileResult();
  m.result.pixels.pop_back();
  expectWireError([&] { decodeTileResult(decodeMessage(encodeTileResult(m))); },
                  "TileResult message: tile 42 is 3x2 but carries 5 pixels");
  m.result.pixels.resize(7);
  EXPECT_THROW(decodeTileResult(decodeMessage(encodeTileResult(m))), WireError);
}

TEST(Messages, InsaneRectanglesAreRejected) {
  const TileRect bad[] = {
      {0, 0, 0, 4},  {0, 0, 4, 0},         {0, 0, -1, 4},        {-1, 0, 4, 4},
      {0, -1, 4, 4}, {0, 0, 65536, 65536}, {INT32_MAX, 0, 1, 1}, {0, INT32_MAX - 1, 1, 2}};
  for (const TileRect& rect : bad) {
    const Message job = decodeMessage(encodeTileJob({0, 0, rect}));
    expectWireError([&] { decodeTileJob(job); }, "invalid tile rectangle");
  }
}

// The envelope's checksum protects against transmission errors; these payloads have valid
// checksums, so only the payload checks stand between them and the renderer.
TEST(Messages, TileResultWithAHugePixelCountThrowsWithoutAllocating) {
  const Message m = handMade(MessageType::TileResult, [](ByteWriter& w) {
    w.writeU32(0);
    w.writeU32(0);
    for (int v : {0, 0, 4, 4}) w.writeI32(v);
    w.writeU64(uint64_t{1} << 60);
    w.writeU64(0);
  });
  expectWireError([&] { decodeTileResult(m); }, "corrupt element count 1152921504606846976");
}

TEST(Messages, TrailingPayloadBytesAreRejected) {
  const Message job = handMade(MessageType::TileJob, [](ByteWriter& w) {
    w.writeU32(0);
    w.writeU32(0);
    for (int v : {0, 0, 4, 4}) w.writeI32(v);
    w.writeU8(0);
  });
  expectWireError([&] { decodeTileJob(job); }, "TileJob message: unexpected trailing data");
  const Message shutdown = handMade(MessageType::Shutdown, [](ByteWriter& w) { w.writeU8(0); });
  expectWireError([&] { decodeShutdown(shutdown); }, "unexpected trailing data");
}

TEST(Messages, ReadyValuesAreChecked) {
  expectWireError(
      [] {
        decodeReady(decodeMessage(encodeReady({1.0, -1})));
      },
      "invalid thread count -1");
  for (double seconds : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(decodeReady(decodeMessage(encodeReady({seconds, 1}))), WireError) << seconds;
  }
}

TEST(Messages, TileTimeMustBeFiniteAndNonNegative) {
  TileResultMessage m = sampleTileResult();
  m.result.seconds = -0.5;
  EXPECT_THROW(decodeTileResult(decodeMessage(encodeTileResult(m))), WireError);
  m.result.seconds = std::nan("");
  EXPECT_THROW(decodeTileResult(decodeMessage(encodeTileResult(m))), WireError);
}

TEST(Messages, ProgressRoundTripsAndRejectsCorruption) {
  const ProgressMessage progress{7, 12345678901ull, {3, 1, 4, 1, 5}};
  std::vector<uint8_t> bytes = encodeProgress(progress);
  const ProgressMessage back = decodeProgress(decodeMessage(bytes));
  EXPECT_EQ(back.frame, 7u);
  EXPECT_EQ(back.jobsReceived, progress.jobsReceived);
  EXPECT_EQ(back.heldTiles, progress.heldTiles);
  EXPECT_EQ(decodeProgress(decodeMessage(encodeProgress({}))).heldTiles.size(), 0u);
  bytes.back() ^= 0x01;
  EXPECT_THROW(decodeMessage(bytes), WireError);
  EXPECT_THROW(decodeProgress(decodeMessage(encodeShutdown())), WireError);
  EXPECT_STREQ(messageTypeName(MessageType::Progress), "Progress");
}

TEST(Messages, MessageStructsMatchTheCodec) {
#if defined(__GLIBCXX__) && UINTPTR_MAX == UINT64_MAX
  const char* update =
      "a message struct changed: update common/wire/Messages.cpp and this test's sizes";
  EXPECT_EQ(sizeof(TileRect), 16u) << update;
  EXPECT_EQ(sizeof(RayCounters), 24u) << update;
  EXPECT_EQ(sizeof(TileResult), 80u) << update;
  EXPECT_EQ(sizeof(TileJobMessage), 32u) << update;
  EXPECT_EQ(sizeof(PhotonJobMessage), 24u) << update;
  EXPECT_EQ(sizeof(PhotonShareMessage), 88u) << update;
  EXPECT_EQ(sizeof(PhotonMapMessage), 48u) << update;
  EXPECT_EQ(sizeof(TileResultMessage), 88u) << update;
  EXPECT_EQ(sizeof(ReadyMessage), 16u) << update;
  EXPECT_EQ(sizeof(ErrorMessage), 32u) << update;
  EXPECT_EQ(sizeof(ProgressMessage), 40u) << update;
#else
  GTEST_SKIP() << "sizes recorded for 64-bit libstdc++";
#endif
}

}  // namespace
}  // namespace prism::wire

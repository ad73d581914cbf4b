#include "wire/Messages.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "image/DisplayBytes.h"

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
  m.result.rays = {6, 12, 0x1234567890ull, 3};
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
            header(kMagic, kVersion, 6, 1, 0xAF63DC4C8601EC8Cull));
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

// The list's columns agree with each other: work goes to a slave and its answers come back;
// the start of a run is Hello, the scene and the go-ahead, and Ready ends it; every number
// of the list is below firstUnusedTypeNumber, and that one is unknown.
TEST(Messages, EachTypeSaysWhichWayWhenAndWhatFor) {
  using enum MessageType;
  int types = 0;
  forEachMessageType([&](auto type) {
    const MessageType t = MessageTraits<typename decltype(type)::type>::kType;
    const MessageKind kind = kindOf(t);
    SCOPED_TRACE(messageTypeName(t));
    if (kind.role == Role::Work) EXPECT_EQ(kind.direction, Direction::ToSlave);
    if (kind.role == Role::Answer) EXPECT_EQ(kind.direction, Direction::ToMaster);
    if (kind.role != Role::Control) EXPECT_EQ(kind.phase, Phase::Run);
    EXPECT_TRUE(isKnownType(static_cast<uint16_t>(t)));
    EXPECT_LT(static_cast<uint16_t>(t), firstUnusedTypeNumber());
    ++types;
  });
  EXPECT_GT(types, 0);
  EXPECT_FALSE(isKnownType(firstUnusedTypeNumber()));
  for (MessageType t : {Hello, SceneAccepted, Ready}) {
    EXPECT_TRUE(goesTo(t, Direction::ToMaster) && !goesTo(t, Direction::ToSlave));
    EXPECT_TRUE(belongsTo(t, Phase::SetUp) && !belongsTo(t, Phase::Run));
  }
  for (MessageType t : {Scene, BuildGeometry, Geometry}) {
    EXPECT_TRUE(goesTo(t, Direction::ToSlave) && !goesTo(t, Direction::ToMaster));
    EXPECT_TRUE(belongsTo(t, Phase::SetUp));
  }
  EXPECT_EQ(kindOf(TileJob).role, Role::Work);
  EXPECT_EQ(kindOf(TileResult).role, Role::Answer);
  EXPECT_TRUE(belongsTo(Error, Phase::SetUp) && belongsTo(Error, Phase::Run) &&
              belongsTo(Error, Phase::ShutDown));
  EXPECT_TRUE(goesTo(Shutdown, Direction::ToSlave) && goesTo(Shutdown, Direction::ToMaster));
}

TEST(Messages, TileJobRoundTrips) {
  const TileJobMessage job{3, 17, {128, 64, 32, 16}};
  const Message m = decodeMessage(encode(job));
  EXPECT_EQ(m.type, MessageType::TileJob);
  const TileJobMessage back = decode<TileJobMessage>(m);
  EXPECT_EQ(back.frame, 3u);
  EXPECT_EQ(back.tileIndex, 17u);
  EXPECT_EQ(back.rect.x, 128);
  EXPECT_EQ(back.rect.y, 64);
  EXPECT_EQ(back.rect.width, 32);
  EXPECT_EQ(back.rect.height, 16);
}

TEST(Messages, TileResultRoundTripsBitExact) {
  const TileResultMessage sent = sampleTileResult();
  const TileResultMessage back = decode<TileResultMessage>(decodeMessage(encode(sent)));
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
  EXPECT_EQ(back.result.rays.nonFinite, sent.result.rays.nonFinite);
  EXPECT_EQ(back.result.seconds, sent.result.seconds);
}

TEST(Messages, ReadyErrorAndShutdownRoundTrip) {
  const ReadyMessage ready =
      decode<ReadyMessage>(decodeMessage(encode(ReadyMessage{1.25, 16, 0.5, 0.125})));
  EXPECT_EQ(ready.buildSeconds, 1.25);
  EXPECT_EQ(ready.threads, 16);
  EXPECT_EQ(ready.startSeconds, 0.5);
  EXPECT_EQ(ready.mpiInitSeconds, 0.125);
  EXPECT_EQ(decode<ReadyMessage>(decodeMessage(encode(ReadyMessage{1.25, 16}))).startSeconds,
            -1.0);  // unknown

  const std::string text = "scene.yaml:3:7: unknown material 'glas'\n\ttab and \xC3\xA9";
  EXPECT_EQ(decode<ErrorMessage>(decodeMessage(encode(ErrorMessage{text}))).text, text);
  EXPECT_EQ(decode<ErrorMessage>(decodeMessage(encode(ErrorMessage{""}))).text, "");

  const std::vector<uint8_t> shutdown = encode(ShutdownMessage{});
  EXPECT_EQ(shutdown.size(), kHeaderSize);
  const Message m = decodeMessage(shutdown);
  EXPECT_EQ(m.type, MessageType::Shutdown);
  EXPECT_TRUE(m.payload.empty());
  EXPECT_NO_THROW(decode<ShutdownMessage>(m));
}

TEST(Messages, EnvelopeErrorsSayWhatIsWrong) {
  const std::vector<uint8_t> good = encode(ErrorMessage{"x"});
  expectWireError([&] { decodeMessage(good.data(), 10); },
                  "message too short for a header: 10 bytes, a header needs 24");

  std::vector<uint8_t> bad = good;
  bad[0] = 'Q';
  expectWireError([&] { decodeMessage(bad); }, "bad magic 0x4D535251");

  // Every older version and a newer one are refused by name.
  for (uint16_t version = 1; version <= kVersion + 1; ++version) {
    if (version == kVersion) continue;
    bad = header(kMagic, version, 6, 0, fnv1a64(nullptr, 0));
    expectWireError([&] { decodeMessage(bad); }, "message version " + std::to_string(version) +
                                                     ", this build speaks " +
                                                     std::to_string(kVersion));
  }

  // Below the list's first number, past its highest, and the largest.
  for (uint16_t type : {uint16_t{0}, firstUnusedTypeNumber(), uint16_t{0xFFFF}}) {
    bad = header(kMagic, kVersion, type, 0, fnv1a64(nullptr, 0));
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
  const Message ready = decodeMessage(encode(ReadyMessage{0.5, 2}));
  expectWireError([&] { decode<TileJobMessage>(ready); }, "expected a TileJob message, got Ready");
  expectWireError([&] { decode<TileResultMessage>(ready); },
                  "expected a TileResult message, got Ready");
  expectWireError([&] { decode<ErrorMessage>(ready); }, "expected a Error message, got Ready");
  expectWireError([&] { decodeScene(ready); }, "expected a Scene message, got Ready");
  expectWireError([&] { decode<ShutdownMessage>(ready); },
                  "expected a Shutdown message, got Ready");
  const Message shutdown = decodeMessage(encode(ShutdownMessage{}));
  expectWireError([&] { decode<ReadyMessage>(shutdown); },
                  "expected a Ready message, got Shutdown");
}

TEST(Messages, EverySingleByteCorruptionOfATileResultIsRejected) {
  const std::vector<uint8_t> good = encode(sampleTileResult());
  ASSERT_NO_THROW(decode<TileResultMessage>(decodeMessage(good)));
  for (size_t i = 0; i < good.size(); ++i) {
    for (int mask : {0x01, 0x02, 0x04, 0x08, 0x10, 0x20, 0x40, 0x80, 0xFF}) {
      std::vector<uint8_t> bad = good;
      bad[i] ^= static_cast<uint8_t>(mask);
      EXPECT_THROW(decode<TileResultMessage>(decodeMessage(bad)), WireError)
          << "byte " << i << " xor " << mask;
    }
  }
}

TEST(Messages, EveryTruncationOfATileResultIsRejected) {
  const std::vector<uint8_t> good = encode(sampleTileResult());
  for (size_t length = 0; length < good.size(); ++length) {
    EXPECT_THROW(decode<TileResultMessage>(decodeMessage(good.data(), length)), WireError)
        << length;
  }
}

TEST(Messages, TileResultPixelCountMustMatchTheRectangle) {
  TileResultMessage m = sampleTileResult();
  m.result.pixels.pop_back();
  expectWireError([&] { decode<TileResultMessage>(decodeMessage(encode(m))); },
                  "TileResult message: tile 42 is 3x2 but carries 5 pixels");
  m.result.pixels.resize(7);
  EXPECT_THROW(decode<TileResultMessage>(decodeMessage(encode(m))), WireError);
}

TEST(Messages, InsaneRectanglesAreRejected) {
  const TileRect bad[] = {
      {0, 0, 0, 4},  {0, 0, 4, 0},         {0, 0, -1, 4},        {-1, 0, 4, 4},
      {0, -1, 4, 4}, {0, 0, 65536, 65536}, {INT32_MAX, 0, 1, 1}, {0, INT32_MAX - 1, 1, 2}};
  for (const TileRect& rect : bad) {
    const Message job = decodeMessage(encode(TileJobMessage{0, 0, rect}));
    expectWireError([&] { decode<TileJobMessage>(job); }, "invalid tile rectangle");
  }
}

// The envelope's checksum protects against transmission errors; these payloads have valid
// checksums, so only the payload checks stand between them and the renderer.
TEST(Messages, TileResultWithAHugePixelCountThrowsWithoutAllocating) {
  const Message m = handMade(MessageType::TileResult, [](ByteWriter& w) {
    w.writeU32(0);
    w.writeU32(0);
    for (int v : {0, 0, 4, 4}) w.writeI32(v);
    w.writeF32(0.0f);  // radiance
    w.writeU64(uint64_t{1} << 60);
    w.writeU64(0);
  });
  expectWireError([&] { decode<TileResultMessage>(m); },
                  "corrupt element count 1152921504606846976");
}

// A frame that is only shown travels as display bytes: 3 a pixel, and what arrives shows as
// what was sent (the same bytes at the same exposure), whatever the radiance was.
TEST(Messages, ATileShownOnlyTravelsAsDisplayBytesThatShowTheSame) {
  TileResultMessage sent = sampleTileResult();
  sent.result.rect = {0, 0, 16, 16};
  sent.result.pixels.resize(256);
  for (size_t i = 0; i < 256; ++i) {
    const float v = 1e-4f * static_cast<float>(i * i);  // 0 to 6.5: dark, mid-tones, clipped
    sent.result.pixels[i] = Color(v, 0.5f * v, 2.0f * v);
  }
  sent.result.pixels[3] = Color(std::numeric_limits<float>::quiet_NaN(), -1.0f, 1e30f);
  const size_t asRadiance = encode(sent).size();
  sent.displayExposure = 1.5f;
  const std::vector<uint8_t> bytes = encode(sent);
  EXPECT_EQ(asRadiance - bytes.size(), 256u * (12 - 3));
  const TileResultMessage back = decode<TileResultMessage>(decodeMessage(bytes));
  EXPECT_EQ(back.displayExposure, 1.5f);
  EXPECT_EQ(back.result.rays.shadow, sent.result.rays.shadow);
  ASSERT_EQ(back.result.pixels.size(), 256u);
  EXPECT_EQ(toDisplayBytes(back.result.pixels, 1.5f), toDisplayBytes(sent.result.pixels, 1.5f));
  EXPECT_NE(back.result.pixels, sent.result.pixels);  // radiance itself is not kept

  for (const float exposure : {-1.0f, std::numeric_limits<float>::infinity()}) {
    const Message m = handMade(MessageType::TileResult, [&](ByteWriter& w) {
      w.writeU32(0);
      w.writeU32(0);
      for (int v : {0, 0, 1, 1}) w.writeI32(v);
      w.writeF32(exposure);
    });
    expectWireError([&] { decode<TileResultMessage>(m); }, "invalid display exposure");
  }
  const Message ragged = handMade(MessageType::TileResult, [](ByteWriter& w) {
    w.writeU32(0);
    w.writeU32(5);
    for (int v : {0, 0, 1, 1}) w.writeI32(v);
    w.writeF32(1.0f);
    w.writeU8s({1, 2, 3, 4});
  });
  expectWireError([&] { decode<TileResultMessage>(ragged); },
                  "display bytes of tile 5 are 4, not 3 a pixel");
}

TEST(Messages, TrailingPayloadBytesAreRejected) {
  const Message job = handMade(MessageType::TileJob, [](ByteWriter& w) {
    w.writeU32(0);
    w.writeU32(0);
    for (int v : {0, 0, 4, 4}) w.writeI32(v);
    w.writeU32(0);           // pass
    w.writeU8(kTermDirect);  // terms
    w.writeU8(0);            // one byte too many
  });
  expectWireError([&] { decode<TileJobMessage>(job); },
                  "TileJob message: unexpected trailing data");
  const Message shutdown = handMade(MessageType::Shutdown, [](ByteWriter& w) { w.writeU8(0); });
  expectWireError([&] { decode<ShutdownMessage>(shutdown); }, "unexpected trailing data");
}

TEST(Messages, ReadyValuesAreChecked) {
  expectWireError(
      [] {
        decode<ReadyMessage>(decodeMessage(encode(ReadyMessage{1.0, -1})));
      },
      "invalid thread count -1");
  for (double seconds : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(decode<ReadyMessage>(decodeMessage(encode(ReadyMessage{seconds, 1}))), WireError)
        << seconds;
    EXPECT_THROW(decode<ReadyMessage>(decodeMessage(encode(ReadyMessage{1.0, 1, 1.0, seconds}))),
                 WireError)
        << seconds;
  }
  for (double start : {-0.5, -2.0, std::nan("")}) {  // -1 alone means "not known"
    EXPECT_THROW(decode<ReadyMessage>(decodeMessage(encode(ReadyMessage{1.0, 1, start}))),
                 WireError)
        << start;
  }
}

TEST(Messages, TileTimeMustBeFiniteAndNonNegative) {
  TileResultMessage m = sampleTileResult();
  m.result.seconds = -0.5;
  EXPECT_THROW(decode<TileResultMessage>(decodeMessage(encode(m))), WireError);
  m.result.seconds = std::nan("");
  EXPECT_THROW(decode<TileResultMessage>(decodeMessage(encode(m))), WireError);
}

TEST(Messages, ProgressRoundTripsAndRejectsCorruption) {
  const ProgressMessage progress{7, 12345678901ull, {3, 1, 4, 1, 5}};
  std::vector<uint8_t> bytes = encode(progress);
  const ProgressMessage back = decode<ProgressMessage>(decodeMessage(bytes));
  EXPECT_EQ(back.frame, 7u);
  EXPECT_EQ(back.jobsReceived, progress.jobsReceived);
  EXPECT_EQ(back.heldTiles, progress.heldTiles);
  EXPECT_EQ(decode<ProgressMessage>(decodeMessage(encode(ProgressMessage{}))).heldTiles.size(), 0u);
  bytes.back() ^= 0x01;
  EXPECT_THROW(decodeMessage(bytes), WireError);
  EXPECT_THROW(decode<ProgressMessage>(decodeMessage(encode(ShutdownMessage{}))), WireError);
  EXPECT_STREQ(messageTypeName(MessageType::Progress), "Progress");
}

TEST(Messages, ViewRoundTripsAndRejectsNonsense) {
  ViewMessage m;
  m.frame = 41;
  m.liveFrom = 40;
  m.view.camera.position = Vec3(1.0f, 2.0f, 3.0f);
  m.view.camera.lookAt = Vec3(-1.0f, 0.5f, 0.0f);
  m.view.camera.fovDegrees = 33.0f;
  m.view.camera.projection = Projection::Orthographic;
  m.view.width = 160;
  m.view.height = 90;
  m.view.samplesPerPixel = 3;
  m.view.seed = 0xDEADBEEFCAFEull;
  m.view.debugView = DebugView::Normals;
  m.view.causticMapBlur = false;
  m.view.jitterSingleSample = true;
  m.view.displayExposure = 0.75f;
  const ViewMessage back = decode<ViewMessage>(decodeMessage(encode(m)));
  EXPECT_EQ(back.view.displayExposure, 0.75f);
  EXPECT_EQ(back.frame, 41u);
  EXPECT_EQ(back.liveFrom, 40u);
  EXPECT_EQ(back.view.camera.position, m.view.camera.position);
  EXPECT_EQ(back.view.camera.lookAt, m.view.camera.lookAt);
  EXPECT_EQ(back.view.camera.fovDegrees, 33.0f);
  EXPECT_EQ(back.view.camera.projection, Projection::Orthographic);
  EXPECT_EQ(back.view.width, 160);
  EXPECT_EQ(back.view.height, 90);
  EXPECT_EQ(back.view.samplesPerPixel, 3);
  EXPECT_EQ(back.view.seed, 0xDEADBEEFCAFEull);
  EXPECT_EQ(back.view.debugView, DebugView::Normals);
  EXPECT_FALSE(back.view.causticMapBlur);
  EXPECT_TRUE(back.view.jitterSingleSample);
  ViewMessage blurred = m;
  blurred.view.causticMapBlur = true;
  EXPECT_TRUE(decode<ViewMessage>(decodeMessage(encode(blurred))).view.causticMapBlur);
  EXPECT_STREQ(messageTypeName(MessageType::View), "View");

  ViewMessage bad = m;
  bad.liveFrom = 42;
  expectWireError([&] { decode<ViewMessage>(decodeMessage(encode(bad))); },
                  "view of frame 41 keeps a later frame 42 running");
  bad = m;
  bad.view.width = 0;
  expectWireError([&] { decode<ViewMessage>(decodeMessage(encode(bad))); },
                  "invalid view size 0x90");
  bad = m;
  bad.view.samplesPerPixel = -2;
  expectWireError([&] { decode<ViewMessage>(decodeMessage(encode(bad))); },
                  "invalid samples per pixel -2");
  bad = m;
  bad.view.displayExposure = std::numeric_limits<float>::quiet_NaN();
  expectWireError([&] { decode<ViewMessage>(decodeMessage(encode(bad))); },
                  "invalid display exposure nan");
  bad = m;
  bad.view.debugView = static_cast<DebugView>(77);
  expectWireError([&] { decode<ViewMessage>(decodeMessage(encode(bad))); },
                  "invalid debug view 77");
  Message flag = decodeMessage(encode(m));
  // The payload ends: debug view (u32), blur switch, jitter flag (bytes), display exposure
  // (f32). DebugView is a byte, so 256 must not read as Image
  // (tests/fuzz/regressions/wire/view-debug-view-256).
  const size_t end = flag.payload.size() - sizeof(float);
  Message wide = flag;
  wide.payload[end - 6] = 0;  // little-endian: 0 + 1 * 256
  wide.payload[end - 5] = 1;
  expectWireError(
      [&] { decode<ViewMessage>(decodeMessage(encodeMessage(MessageType::View, wide.payload))); },
      "invalid debug view 256");
  Message blur = flag;
  blur.payload[end - 2] = 2;
  expectWireError(
      [&] { decode<ViewMessage>(decodeMessage(encodeMessage(MessageType::View, blur.payload))); },
      "invalid caustic-map blur flag 2");
  flag.payload[end - 1] = 3;
  expectWireError(
      [&] { decode<ViewMessage>(decodeMessage(encodeMessage(MessageType::View, flag.payload))); },
      "invalid jitter flag 3");
  EXPECT_THROW(decode<ViewMessage>(decodeMessage(encode(ShutdownMessage{}))), WireError);
}

// ---- caustic passes -------------------------------------------------------------------------

TEST(Messages, PhotonTypeNames) {
  EXPECT_STREQ(messageTypeName(MessageType::PhotonJob), "PhotonJob");
  EXPECT_STREQ(messageTypeName(MessageType::PhotonShare), "PhotonShare");
  EXPECT_STREQ(messageTypeName(MessageType::PhotonMap), "PhotonMap");
}

TEST(Messages, TileJobCarriesItsPassAndLightTerms) {
  for (uint8_t terms : {kTermDirect, kTermCaustics, uint8_t(kTermDirect | kTermCaustics),
                        kTermCausticMap, uint8_t(kTermDirect | kTermCausticMap)}) {
    TileJobMessage job{9, 4, {0, 16, 8, 8}};
    job.pass = 0xDEADBEEF;
    job.terms = terms;
    const TileJobMessage back = decode<TileJobMessage>(decodeMessage(encode(job)));
    EXPECT_EQ(back.frame, 9u);
    EXPECT_EQ(back.tileIndex, 4u);
    EXPECT_EQ(back.pass, 0xDEADBEEFu);
    EXPECT_EQ(back.terms, terms);
  }
  EXPECT_EQ(TileJobMessage{}.terms, kTermDirect);  // a plain tile is direct light
}

TEST(Messages, TileJobWithoutLightTermsIsRejected) {
  // None, unknown bits, or photon-map and caustic-map caustics at once.
  for (uint8_t terms : {0, 6, 7, 8, 0xFF}) {
    TileJobMessage job{0, 0, {0, 0, 4, 4}};
    job.terms = terms;
    const Message m = decodeMessage(encode(job));
    expectWireError([&] { decode<TileJobMessage>(m); },
                    "TileJob message: invalid light terms " + std::to_string(terms));
  }
}

// Photons with awkward bit patterns: a denormal power, -0 and large coordinates, every
// direction code at its extremes.
std::vector<Photon> samplePhotons() {
  std::vector<Photon> photons(4);
  photons[0].position = {1.5f, -2.25f, 1e30f};
  photons[0].power = {0.125f, 1e-40f, 3.0f};
  photons[0].direction[0] = 0;
  photons[0].direction[1] = 0xFFFF;
  photons[1].position = {-0.0f, 0.0f, -1e-30f};
  photons[1].power = {0.0f, 0.0f, 0.0f};
  photons[1].setDirection(glm::normalize(Vec3(0.3f, -0.9f, -0.1f)));
  photons[2].position = {7, 8, 9};
  photons[2].power = {1e20f, 2e-3f, 0.5f};
  photons[2].direction[0] = 0x8000;
  photons[2].direction[1] = 0x7FFF;
  photons[3] = photons[2];
  photons[3].position.x = 3.0f;
  return photons;
}

void expectSamePhotons(const std::vector<Photon>& a, const std::vector<Photon>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(std::memcmp(&a[i], &b[i], sizeof(Photon)), 0) << "photon " << i;
  }
}

TEST(Messages, PhotonJobRoundTrips) {
  const PhotonJobMessage job{17, 0x123456789ull, 4096, 0x200000000ull};
  const PhotonJobMessage back = decode<PhotonJobMessage>(decodeMessage(encode(job)));
  EXPECT_EQ(back.pass, 17u);
  EXPECT_EQ(back.first, 0x123456789ull);
  EXPECT_EQ(back.count, 4096u);
  EXPECT_EQ(back.photonsPerPass, 0x200000000ull);
  expectWireError(
      [] {
        decode<PhotonJobMessage>(
            decodeMessage(encode(PhotonJobMessage{0, UINT64_MAX - 1, 2, UINT64_MAX})));
      },
      "photon range overflows");
  expectWireError(
      [] {
        decode<PhotonJobMessage>(decodeMessage(encode(PhotonJobMessage{0, 10, 6, 15})));
      },
      "photon range exceeds the budget");
}

TEST(Messages, PhotonShareRoundTripsBitExact) {
  PhotonShareMessage share;
  share.pass = 3;
  share.first = 1000;
  share.count = 500;
  share.photons = samplePhotons();
  share.stats = {500, share.photons.size(), 321, 175};
  share.seconds = 0.0078125;
  const std::vector<uint8_t> bytes = encode(share);
  const PhotonShareMessage back = decode<PhotonShareMessage>(decodeMessage(bytes));
  EXPECT_EQ(back.pass, 3u);
  EXPECT_EQ(back.first, 1000u);
  EXPECT_EQ(back.count, 500u);
  EXPECT_EQ(back.stats.emitted, 500u);
  EXPECT_EQ(back.stats.stored, 4u);
  EXPECT_EQ(back.stats.missed, 321u);
  EXPECT_EQ(back.stats.absorbed, 175u);
  EXPECT_EQ(back.seconds, share.seconds);
  expectSamePhotons(back.photons, share.photons);
  EXPECT_EQ(encode(back), bytes);

  // 28 bytes a photon on the wire too: four photons more cost exactly 4·28 bytes.
  PhotonShareMessage more = share;
  more.photons.insert(more.photons.end(), share.photons.begin(), share.photons.end());
  more.stats.stored = more.photons.size();
  EXPECT_EQ(encode(more).size() - bytes.size(), 4 * sizeof(Photon));
}

TEST(Messages, PhotonShareMustCarryTheStoredCount) {
  PhotonShareMessage share;
  share.photons = samplePhotons();
  share.stats.stored = 3;
  expectWireError([&] { decode<PhotonShareMessage>(decodeMessage(encode(share))); },
                  "carries 4 photons but reports 3 stored");
}

TEST(Messages, PhotonMapRoundTripsBitExact) {
  PhotonMapMessage map;
  map.pass = 12;
  map.gather = {true, 37, 0.015625f, PhotonFilter::Epanechnikov, 0.375f};
  map.photons = samplePhotons();
  const std::vector<uint8_t> bytes = encode(map);
  const PhotonMapMessage back = decode<PhotonMapMessage>(decodeMessage(bytes));
  EXPECT_EQ(back.pass, 12u);
  EXPECT_TRUE(back.gather.fixedRadius);
  EXPECT_EQ(back.gather.k, 37);
  EXPECT_EQ(std::bit_cast<uint32_t>(back.gather.radius), std::bit_cast<uint32_t>(0.015625f));
  EXPECT_EQ(back.gather.filter, PhotonFilter::Epanechnikov);
  EXPECT_EQ(back.gather.radiusScale, 0.375f);
  expectSamePhotons(back.photons, map.photons);
  EXPECT_EQ(encode(back), bytes);

  EXPECT_FALSE(back.keep);
  map.keep = true;
  EXPECT_TRUE(decode<PhotonMapMessage>(decodeMessage(encode(map))).keep);

  map.photons.clear();  // a pass that stored nothing is still a valid map
  EXPECT_TRUE(decode<PhotonMapMessage>(decodeMessage(encode(map))).photons.empty());
}

TEST(Messages, PhotonMapAgainRoundTripsAndIsChecked) {
  const std::vector<uint8_t> bytes = encode(PhotonMapAgainMessage{41, 7});
  const PhotonMapAgainMessage back = decode<PhotonMapAgainMessage>(decodeMessage(bytes));
  EXPECT_EQ(back.pass, 41u);
  EXPECT_EQ(back.keptPass, 7u);
  EXPECT_EQ(encode(back), bytes);
  EXPECT_STREQ(messageTypeName(MessageType::PhotonMapAgain), "PhotonMapAgain");
  expectWireError([&] { decode<PhotonMapAgainMessage>(decodeMessage(encode(ShutdownMessage{}))); },
                  "expected a PhotonMapAgain message, got Shutdown");
  const std::vector<uint8_t> shorter =
      encodeMessage(MessageType::PhotonMapAgain, {1, 0, 0, 0, 2, 0, 0});
  EXPECT_THROW(decode<PhotonMapAgainMessage>(decodeMessage(shorter)), WireError);
}

TEST(Messages, PhotonRadiiMessagesRoundTripAndAreChecked) {
  const std::vector<uint8_t> job = encode(PhotonRadiiJobMessage{12, 128, 4000});
  const PhotonRadiiJobMessage jobBack = decode<PhotonRadiiJobMessage>(decodeMessage(job));
  EXPECT_EQ(jobBack.pass, 12u);
  EXPECT_EQ(jobBack.first, 128u);
  EXPECT_EQ(jobBack.count, 4000u);
  EXPECT_EQ(encode(jobBack), job);
  expectWireError(
      [&] {
        decode<PhotonRadiiJobMessage>(
            decodeMessage(encode(PhotonRadiiJobMessage{1, 10, UINT64_MAX})));
      },
      "PhotonRadiiJob message: radii range overflows");

  const std::vector<float> radii = {0.5f, 0.0f, 1e-7f, 0.25f};
  const std::vector<uint8_t> share = encode(PhotonRadiiShareMessage{12, 128, radii});
  const PhotonRadiiShareMessage shareBack = decode<PhotonRadiiShareMessage>(decodeMessage(share));
  EXPECT_EQ(shareBack.pass, 12u);
  EXPECT_EQ(shareBack.first, 128u);
  EXPECT_EQ(shareBack.radii, radii);
  EXPECT_EQ(encode(shareBack), share);

  const std::vector<uint8_t> all = encode(PhotonRadiiMessage{12, radii});
  const PhotonRadiiMessage allBack = decode<PhotonRadiiMessage>(decodeMessage(all));
  EXPECT_EQ(allBack.pass, 12u);
  EXPECT_EQ(allBack.radii, radii);
  EXPECT_EQ(encode(allBack), all);
  EXPECT_STREQ(messageTypeName(MessageType::PhotonRadiiJob), "PhotonRadiiJob");
  EXPECT_STREQ(messageTypeName(MessageType::PhotonRadiiShare), "PhotonRadiiShare");
  EXPECT_STREQ(messageTypeName(MessageType::PhotonRadii), "PhotonRadii");
  expectWireError([&] { decode<PhotonRadiiMessage>(decodeMessage(share)); },
                  "expected a PhotonRadii message, got PhotonRadiiShare");

  // A radius the gather could not use (negative, NaN, infinite) is refused, naming which.
  const float nan = std::nanf(""), inf = std::numeric_limits<float>::infinity();
  for (float bad : {-0.5f, nan, inf}) {
    std::vector<float> spoilt = radii;
    spoilt[2] = bad;
    expectWireError(
        [&] {
          decode<PhotonRadiiMessage>(decodeMessage(encode(PhotonRadiiMessage{3, spoilt})));
        },
        "PhotonRadii message: radius 2 is negative or not finite");
    expectWireError(
        [&] {
          decode<PhotonRadiiShareMessage>(
              decodeMessage(encode(PhotonRadiiShareMessage{3, 0, spoilt})));
        },
        "PhotonRadiiShare message: radius 2 is negative or not finite");
  }
  // A count larger than the bytes present.
  std::vector<uint8_t> truncated = decodeMessage(all).payload;
  truncated.resize(truncated.size() - 4);
  EXPECT_THROW(
      decode<PhotonRadiiMessage>(decodeMessage(encodeMessage(MessageType::PhotonRadii, truncated))),
      WireError);
}

TEST(Messages, PhotonsWithCorruptPowerOrPositionAreRejected) {
  const float nan = std::nanf(""), inf = std::numeric_limits<float>::infinity();
  const auto corrupt = [](const std::function<void(Photon&)>& spoil) {
    PhotonMapMessage map;
    map.gather = {false, 10, 0.5f, PhotonFilter::Cone};
    map.photons = samplePhotons();
    spoil(map.photons[2]);
    return decodeMessage(encode(map));
  };
  const std::function<void(Photon&)> spoils[] = {
      [](Photon& p) { p.power.y = -0.5f; },   [](Photon& p) { p.power.z = -1e-40f; },
      [&](Photon& p) { p.power.x = nan; },    [&](Photon& p) { p.power.x = inf; },
      [&](Photon& p) { p.position.z = nan; }, [&](Photon& p) { p.position.y = -inf; }};
  for (const auto& spoil : spoils) {
    const Message m = corrupt(spoil);
    expectWireError([&] { decode<PhotonMapMessage>(m); },
                    "PhotonMap message: photon 2 has a non-finite");
  }
  // The share uses the same photon reader.
  PhotonShareMessage share;
  share.photons = samplePhotons();
  share.photons[0].power.x = -1.0f;
  share.stats.stored = share.photons.size();
  expectWireError([&] { decode<PhotonShareMessage>(decodeMessage(encode(share))); },
                  "photon 0 has a non-finite position or a power that is negative");
}

TEST(Messages, PhotonMapGatherSettingsAreChecked) {
  PhotonMapMessage map;
  map.photons = samplePhotons();
  for (int k : {0, -1, INT32_MIN}) {
    map.gather = {false, k, 0.5f, PhotonFilter::Box};
    const Message m = decodeMessage(encode(map));
    expectWireError([&] { decode<PhotonMapMessage>(m); },
                    "invalid gather settings (k " + std::to_string(k));
  }
  for (float radius : {0.0f, -1.0f, std::nanf(""), std::numeric_limits<float>::infinity()}) {
    map.gather = {true, 5, radius, PhotonFilter::Box};
    const Message m = decodeMessage(encode(map));
    expectWireError([&] { decode<PhotonMapMessage>(m); }, "invalid gather settings");
  }
  for (float scale : {0.0f, -0.5f, std::nanf(""), std::numeric_limits<float>::infinity()}) {
    map.gather = {false, 5, 0.5f, PhotonFilter::Cone, scale};
    const Message m = decodeMessage(encode(map));
    expectWireError([&] { decode<PhotonMapMessage>(m); }, "invalid gather settings");
  }
  for (uint32_t filter : {3u, 0xFFFFFFFFu}) {
    map.gather = {false, 5, 0.5f, static_cast<PhotonFilter>(filter)};
    const Message m = decodeMessage(encode(map));
    expectWireError([&] { decode<PhotonMapMessage>(m); },
                    "invalid photon filter " + std::to_string(filter));
  }
}

TEST(Messages, PhotonMessagesRejectEveryTruncationAndTheWrongType) {
  PhotonMapMessage map;
  map.gather = {false, 10, 0.5f, PhotonFilter::Cone};
  map.photons = samplePhotons();
  const std::vector<uint8_t> good = encode(map);
  for (size_t length = 0; length < good.size(); ++length) {
    EXPECT_THROW(decode<PhotonMapMessage>(decodeMessage(good.data(), length)), WireError) << length;
  }
  const Message job = decodeMessage(encode(PhotonJobMessage{1, 2, 3, 5}));
  expectWireError([&] { decode<PhotonMapMessage>(job); },
                  "expected a PhotonMap message, got PhotonJob");
  expectWireError([&] { decode<PhotonShareMessage>(job); },
                  "expected a PhotonShare message, got PhotonJob");
  expectWireError([&] { decode<PhotonJobMessage>(decodeMessage(good)); },
                  "expected a PhotonJob message, got PhotonMap");
}

// A corrupted photon count must fail on the size check, before anything is allocated.
TEST(Messages, PhotonMapWithAHugePhotonCountThrowsWithoutAllocating) {
  const Message m = handMade(MessageType::PhotonMap, [](ByteWriter& w) {
    w.writeU32(0);
    w.writeBool(false);
    w.writeI32(10);
    w.writeF32(0.5f);
    w.writeU32(1);
    w.writeF32(1.0f);    // radius scale
    w.writeBool(false);  // automatic k
    w.writeBool(false);  // keep
    w.writeU64(uint64_t{1} << 60);
  });
  expectWireError([&] { decode<PhotonMapMessage>(m); },
                  "corrupt element count 1152921504606846976");
}

// The field lists name every field in a structured binding, so a new field breaks their build;
// these sizes catch a field whose type changed, which changes the wire form without a word.
TEST(Messages, MessageStructsMatchTheCodec) {
#if defined(__GLIBCXX__) && UINTPTR_MAX == UINT64_MAX
  const char* update =
      "a message struct changed: check its field list (common/wire/Messages.h, MessageParts.h), "
      "bump kVersion if its wire form changed, and update this test's sizes";
  EXPECT_EQ(sizeof(TileRect), 16u) << update;
  EXPECT_EQ(sizeof(RayCounters), 32u) << update;
  EXPECT_EQ(sizeof(TileResult), 88u) << update;
  EXPECT_EQ(sizeof(TileJobMessage), 32u) << update;
  EXPECT_EQ(sizeof(PhotonJobMessage), 32u) << update;
  EXPECT_EQ(sizeof(PhotonShareMessage), 88u) << update;
  EXPECT_EQ(sizeof(PhotonMapMessage), 64u) << update;
  EXPECT_EQ(sizeof(PhotonMapAgainMessage), 8u) << update;
  EXPECT_EQ(sizeof(PhotonRadiiJobMessage), 24u) << update;
  EXPECT_EQ(sizeof(PhotonRadiiShareMessage), 40u) << update;
  EXPECT_EQ(sizeof(PhotonRadiiMessage), 32u) << update;
  EXPECT_EQ(sizeof(TileResultMessage), 104u) << update;
  EXPECT_EQ(sizeof(ReadyMessage), 32u) << update;
  EXPECT_EQ(sizeof(ErrorMessage), 32u) << update;
  EXPECT_EQ(sizeof(ProgressMessage), 40u) << update;
  EXPECT_EQ(sizeof(RenderView), 128u) << update;
  EXPECT_EQ(sizeof(ViewMessage), 136u) << update;
#else
  GTEST_SKIP() << "sizes recorded for 64-bit libstdc++";
#endif
}

TEST(Messages, EchoRoundTripsWithItsPadding) {
  const EchoMessage m{77, std::string(5000, 'x')};
  const std::vector<uint8_t> bytes = encode(m);
  EXPECT_EQ(bytes.size(), kHeaderSize + 4 + 4 + 5000);
  const EchoMessage back = decode<EchoMessage>(decodeMessage(bytes));
  EXPECT_EQ(back.sequence, 77u);
  EXPECT_EQ(back.padding, m.padding);
  EXPECT_STREQ(messageTypeName(MessageType::Echo), "Echo");
  expectWireError([&] { decode<EchoMessage>(decodeMessage(encode(ShutdownMessage{}))); },
                  "expected a Echo message, got Shutdown");
}

TEST(Messages, PhotonCancelRoundTripsAndIsChecked) {
  const std::vector<uint8_t> bytes = encode(PhotonCancelMessage{41});
  EXPECT_EQ(bytes.size(), kHeaderSize + 4);
  EXPECT_EQ(decode<PhotonCancelMessage>(decodeMessage(bytes)).pass, 41u);
  EXPECT_STREQ(messageTypeName(MessageType::PhotonCancel), "PhotonCancel");
  expectWireError([&] { decode<PhotonCancelMessage>(decodeMessage(encode(ShutdownMessage{}))); },
                  "expected a PhotonCancel message, got Shutdown");
  const std::vector<uint8_t> longer = encodeMessage(MessageType::PhotonCancel, {1, 0, 0, 0, 0});
  EXPECT_THROW(decode<PhotonCancelMessage>(decodeMessage(longer)), WireError);
}

}  // namespace
}  // namespace prism::wire

// Each of the slave's message handlers (slave/SlaveHandlers.cpp), one message type at a time,
// against the real session over the loopback transport: the test plays rank 0 and checks what
// the slave sends back (tiles against the same tiles rendered here, bit for bit; photon shares
// against the photons traced here).
#include "slave/SlaveHandlers.h"

#include <gtest/gtest.h>

#include <cstring>
#include <map>

#include "caustics/GatherRadius.h"
#include "caustics/PhotonGather.h"
#include "caustics/PhotonMap.h"
#include "caustics/PhotonRadii.h"
#include "caustics/PhotonTracer.h"
#include "render/RenderPass.h"
#include "slave/SlaveUnderTest.h"

namespace prism {
namespace {

using test::SlaveUnderTest;
using Type = wire::MessageType;

wire::TileJobMessage tileJob(uint32_t frame, uint32_t tile, TileRect rect, uint32_t pass = 0,
                             uint8_t terms = wire::kTermDirect) {
  return {frame, tile, rect, pass, terms};
}

// The results the slave sends for `jobs` (in any order), by tile index.
std::map<uint32_t, wire::TileResultMessage> resultsOf(
    SlaveUnderTest& slave, const std::vector<wire::TileJobMessage>& jobs) {
  for (const wire::TileJobMessage& job : jobs) slave.send(wire::encode(job));
  std::map<uint32_t, wire::TileResultMessage> results;
  while (results.size() < jobs.size()) {
    const std::optional<wire::Message> m = slave.next(Type::TileResult);
    if (!m) break;
    wire::TileResultMessage result = wire::decode<wire::TileResultMessage>(*m);
    results.emplace(result.result.tileIndex, std::move(result));
  }
  return results;
}

bool samePhotons(const std::vector<Photon>& a, const std::vector<Photon>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Photon)) == 0;
}

TEST(SlaveHandlers, TileJobsComeBackAsTheirTilesRenderedHere) {
  const SceneDescription d = test::smallScene();
  const Scene scene(d);
  SlaveUnderTest slave;
  slave.broadcast(d);
  ASSERT_TRUE(slave.ready());
  const std::vector<wire::TileJobMessage> jobs = {tileJob(1, 0, {0, 0, 32, 24}),
                                                  tileJob(1, 3, {32, 24, 32, 24})};
  const auto results = resultsOf(slave, jobs);
  ASSERT_EQ(results.size(), 2u);
  for (const wire::TileJobMessage& job : jobs) {
    const wire::TileResultMessage& got = results.at(job.tileIndex);
    EXPECT_EQ(got.frame, 1u);
    EXPECT_EQ(got.result.rect.x, job.rect.x);
    EXPECT_EQ(got.result.rect.width, job.rect.width);
    EXPECT_TRUE(test::samePixels(got.result.pixels,
                                 TileRenderer(scene).render(job.tileIndex, job.rect).pixels));
  }
}

// A View's camera, size and samples replace the scene's for the tiles of its frame.
TEST(SlaveHandlers, AViewGivesTheTilesOfItsFrameItsCamera) {
  const SceneDescription d = test::smallScene();
  const Scene scene(d);
  RenderView view;
  view.camera = d.camera;
  view.camera.position += Vec3(0.3f, -0.2f, 0.5f);
  view.width = 40;
  view.height = 30;
  view.seed = 17;
  SlaveUnderTest slave;
  slave.broadcast(d);
  ASSERT_TRUE(slave.ready());
  slave.send(wire::encode(wire::ViewMessage{5, 5, view}));
  const auto results = resultsOf(slave, {tileJob(5, 2, {8, 8, 16, 16})});
  ASSERT_EQ(results.size(), 1u);
  EXPECT_TRUE(test::samePixels(results.at(2).result.pixels,
                               TileRenderer(scene, view).render(2, {8, 8, 16, 16}).pixels));
}

// The heartbeat names the frame, the jobs of it received and the tiles held: with one render
// thread busy on a long tile, the second is queued, and both are held.
TEST(SlaveHandlers, TheHeartbeatListsTheTilesHeld) {
  SceneDescription d = test::smallScene();
  d.render.samplesPerPixel = 4096;  // seconds a tile, cancelled after its row at Shutdown
  SlaveUnderTest slave;
  slave.broadcast(d);
  ASSERT_TRUE(slave.ready());
  slave.send(wire::encode(tileJob(2, 0, {0, 0, 32, 24})));
  slave.send(wire::encode(tileJob(2, 1, {32, 0, 32, 24})));
  std::optional<wire::ProgressMessage> progress;
  while (const std::optional<wire::Message> m = slave.next(Type::Progress)) {
    progress = wire::decode<wire::ProgressMessage>(*m);
    if (progress->frame == 2 && progress->jobsReceived == 2) break;
  }
  ASSERT_TRUE(progress);
  EXPECT_EQ(progress->frame, 2u);
  EXPECT_EQ(progress->heldTiles, (std::vector<uint32_t>{0, 1}));
  const std::vector<Type> end = slave.shutDown();
  EXPECT_EQ(std::count(end.begin(), end.end(), Type::TileResult), 0);
}

// Before any job the heartbeat still beats, with frame 0 and nothing held; once a frame's tiles
// are back it names none held.
TEST(SlaveHandlers, TheHeartbeatCountsTheJobsOfAFrameAndReleasesDeliveredTiles) {
  SlaveUnderTest slave;
  slave.broadcast(test::smallScene());
  ASSERT_TRUE(slave.ready());
  const std::optional<wire::Message> idle = slave.next(Type::Progress);
  ASSERT_TRUE(idle);
  EXPECT_EQ(wire::decode<wire::ProgressMessage>(*idle).frame, 0u);
  EXPECT_EQ(wire::decode<wire::ProgressMessage>(*idle).jobsReceived, 0u);
  ASSERT_EQ(resultsOf(slave, {tileJob(3, 0, {0, 0, 8, 8}), tileJob(3, 1, {8, 0, 8, 8})}).size(),
            2u);
  std::optional<wire::ProgressMessage> progress;
  while (const std::optional<wire::Message> m = slave.next(Type::Progress)) {
    progress = wire::decode<wire::ProgressMessage>(*m);
    if (progress->frame == 3) break;
  }
  ASSERT_TRUE(progress);
  EXPECT_EQ(progress->jobsReceived, 2u);
  EXPECT_TRUE(progress->heldTiles.empty());
}

// A job of a later frame without a View (`prism render`'s passes) ends the earlier frame: the
// heartbeat names the new frame only, and a late job of the old frame is dropped.
TEST(SlaveHandlers, AJobOfALaterFrameEndsTheEarlierOne) {
  SlaveUnderTest slave;
  slave.broadcast(test::smallScene());
  ASSERT_TRUE(slave.ready());
  ASSERT_EQ(resultsOf(slave, {tileJob(4, 0, {0, 0, 8, 8})}).size(), 1u);
  ASSERT_EQ(resultsOf(slave, {tileJob(6, 1, {8, 0, 8, 8})}).size(), 1u);
  slave.send(wire::encode(tileJob(4, 2, {16, 0, 8, 8})));  // its frame has ended
  slave.send(wire::encode(wire::EchoMessage{1, ""}));
  ASSERT_TRUE(slave.next(Type::Echo));  // the late job was handled before it
  const std::optional<wire::Message> beat = slave.next(Type::Progress);
  ASSERT_TRUE(beat);
  const wire::ProgressMessage p = wire::decode<wire::ProgressMessage>(*beat);
  EXPECT_EQ(p.frame, 6u);  // the only frame running
  EXPECT_EQ(p.jobsReceived, 1u);
  EXPECT_TRUE(p.heldTiles.empty());
  const std::vector<Type> end = slave.shutDown();
  EXPECT_EQ(std::count(end.begin(), end.end(), Type::TileResult), 0);
}

TEST(SlaveHandlers, AnEchoComesStraightBackByteForByte) {
  SlaveUnderTest slave;
  slave.broadcast(test::smallScene());
  ASSERT_TRUE(slave.ready());
  const std::vector<uint8_t> echo = wire::encode(wire::EchoMessage{42, std::string(1000, 'x')});
  slave.send(echo);
  ASSERT_TRUE(slave.next(Type::Echo));
  EXPECT_EQ(slave.raw().back(), echo);
}

// A photon job's share: the photons the same tracer stores here for that range, in order.
TEST(SlaveHandlers, APhotonJobIsAnsweredWithTheSharesPhotons) {
  const SceneDescription d = test::causticScene();
  const Scene scene(d);
  SlaveUnderTest slave;
  slave.broadcast(d);
  ASSERT_TRUE(slave.ready());
  const wire::PhotonJobMessage job{7, 1000, 3000, 8000};
  slave.send(wire::encode(job));
  const std::optional<wire::Message> m = slave.next(Type::PhotonShare);
  ASSERT_TRUE(m);
  const wire::PhotonShareMessage share = wire::decode<wire::PhotonShareMessage>(*m);
  EXPECT_EQ(share.pass, 7u);
  EXPECT_EQ(share.first, 1000u);
  EXPECT_EQ(share.count, 3000u);
  const PhotonTracer tracer(scene, 8000, scene.causticSettings().maxBounces);
  const std::vector<Photon> expected = tracePhotons(tracer, 7, 1000, 3000, 1);
  EXPECT_GT(expected.size(), 0u);
  EXPECT_TRUE(samePhotons(share.photons, expected));
}

// Rank 0 dropped the pass: the share being traced stops and nothing is sent for it.
TEST(SlaveHandlers, ACancelledPhotonPassSendsNothing) {
  SlaveUnderTest slave;
  slave.broadcast(test::causticScene());
  ASSERT_TRUE(slave.ready());
  slave.send(wire::encode(
      wire::PhotonJobMessage{3, 0, 200'000'000, 200'000'000}));  // minutes, uncancelled
  slave.send(wire::encode(wire::PhotonCancelMessage{3}));
  const std::vector<Type> end = slave.shutDown();
  ASSERT_FALSE(end.empty());
  EXPECT_EQ(end.back(), Type::Shutdown);
  EXPECT_EQ(std::count(end.begin(), end.end(), Type::PhotonShare), 0);
}

// A cancel names its pass: another pass's share is still sent.
TEST(SlaveHandlers, ACancelOfAnotherPassLeavesTheShareBeingTraced) {
  SlaveUnderTest slave;
  slave.broadcast(test::causticScene());
  ASSERT_TRUE(slave.ready());
  slave.send(wire::encode(wire::PhotonJobMessage{3, 0, 2000, 2000}));
  slave.send(wire::encode(wire::PhotonCancelMessage{2}));
  const std::optional<wire::Message> m = slave.next(Type::PhotonShare);
  ASSERT_TRUE(m);
  EXPECT_EQ(wire::decode<wire::PhotonShareMessage>(*m).pass, 3u);
}

// Photons of the caustic scene, and gather settings for them.
struct Caustics {
  Caustics() : description(test::causticScene()), scene(description) {
    const PhotonTracer tracer(scene, 20000, scene.causticSettings().maxBounces);
    photons = tracePhotons(tracer, 1, 0, 20000, 1);
    map = std::make_shared<const PhotonMap>(photons);
    gather.k = 50;
    gather.radius = automaticMaxRadius(scene);
  }
  // A tile of pass `pass` with direct light and caustics, rendered here with `estimator`.
  std::vector<Color> tile(uint32_t pass, const std::shared_ptr<const CausticEstimator>& estimator,
                          const TileRect& rect) const {
    const RenderPass renderPass{pass, true, estimator};
    return TileRenderer(scene, renderPass.terms()).render(0, rect).pixels;
  }
  SceneDescription description;
  Scene scene;
  std::vector<Photon> photons;
  std::shared_ptr<const PhotonMap> map;
  PhotonGatherSettings gather;
};

constexpr uint8_t kDirectAndCaustics = wire::kTermDirect | wire::kTermCaustics;
const TileRect kCausticTile{8, 12, 24, 16};

// A fixed-radius map gathers at once: the next tile of its pass renders with it.
TEST(SlaveHandlers, APhotonMapGivesTheTilesOfItsPassTheirCaustics) {
  Caustics c;
  c.gather.fixedRadius = true;
  SlaveUnderTest slave;
  slave.broadcast(c.description);
  ASSERT_TRUE(slave.ready());
  slave.send(wire::encode(wire::PhotonMapMessage{2, c.gather, c.photons, false}));
  const auto results = resultsOf(slave, {tileJob(1, 0, kCausticTile, 2, kDirectAndCaustics)});
  ASSERT_EQ(results.size(), 1u);
  const auto gather = std::make_shared<const PhotonGather>(c.map, c.gather, 1);
  EXPECT_TRUE(test::samePixels(results.at(0).result.pixels, c.tile(2, gather, kCausticTile)));
  EXPECT_FALSE(test::samePixels(results.at(0).result.pixels, c.tile(2, nullptr, kCausticTile)));
}

// Per-photon radii: the slave finds the share it is asked for, then gathers with every radius
// once PhotonRadii brings them.
TEST(SlaveHandlers, APhotonMapWithRadiiGathersOnceTheRadiiCome) {
  Caustics c;
  SlaveUnderTest slave;
  slave.broadcast(c.description);
  ASSERT_TRUE(slave.ready());
  slave.send(wire::encode(wire::PhotonMapMessage{2, c.gather, c.photons, false}));
  slave.send(wire::encode(wire::PhotonRadiiJobMessage{2, 0, c.photons.size()}));
  const std::optional<wire::Message> m = slave.next(Type::PhotonRadiiShare);
  ASSERT_TRUE(m);
  const wire::PhotonRadiiShareMessage share = wire::decode<wire::PhotonRadiiShareMessage>(*m);
  EXPECT_EQ(share.pass, 2u);
  EXPECT_EQ(share.radii,
            photonRadiiShare(*c.map, c.gather.k, c.gather.radius, false, 0, c.photons.size(), 1));
  const std::vector<float> radii = photonRadii(*c.map, c.gather.k, c.gather.radius, false, 1);
  slave.send(wire::encode(wire::PhotonRadiiMessage{2, radii}));
  const auto results = resultsOf(slave, {tileJob(1, 0, kCausticTile, 2, kDirectAndCaustics)});
  ASSERT_EQ(results.size(), 1u);
  const auto gather = std::make_shared<const PhotonGather>(c.map, c.gather, radii, 1);
  EXPECT_TRUE(test::samePixels(results.at(0).result.pixels, c.tile(2, gather, kCausticTile)));
}

// A kept map serves a later pass that names it, after another map has come.
TEST(SlaveHandlers, PhotonMapAgainGathersFromTheKeptMap) {
  Caustics c;
  c.gather.fixedRadius = true;
  SlaveUnderTest slave;
  slave.broadcast(c.description);
  ASSERT_TRUE(slave.ready());
  slave.send(wire::encode(wire::PhotonMapMessage{1, c.gather, c.photons, true}));
  const std::vector<Photon> fewer(c.photons.begin(), c.photons.begin() + c.photons.size() / 4);
  slave.send(wire::encode(wire::PhotonMapMessage{2, c.gather, fewer, false}));
  slave.send(wire::encode(wire::PhotonMapAgainMessage{3, 1}));
  const auto results = resultsOf(slave, {tileJob(1, 0, kCausticTile, 3, kDirectAndCaustics)});
  ASSERT_EQ(results.size(), 1u);
  const auto gather = std::make_shared<const PhotonGather>(c.map, c.gather, 1);
  EXPECT_TRUE(test::samePixels(results.at(0).result.pixels, c.tile(3, gather, kCausticTile)));
}

// The slave's errors name what it lacks; rank 0 reports them and ends the job.
std::string errorFor(std::vector<std::vector<uint8_t>> messages) {
  SlaveUnderTest slave;
  slave.broadcast(test::causticScene());
  EXPECT_TRUE(slave.ready());
  for (std::vector<uint8_t>& m : messages) slave.send(std::move(m));
  const std::optional<wire::Message> error = slave.next(Type::Error);
  const std::vector<Type> end = slave.shutDown();
  EXPECT_EQ(end.back(), Type::Shutdown);  // the error reported, it waits for the shutdown
  EXPECT_EQ(slave.join().exitCode, 1);
  return error ? wire::decode<wire::ErrorMessage>(*error).text : "no error";
}

TEST(SlaveHandlers, ACausticTileWithoutItsMapIsAnError) {
  EXPECT_EQ(errorFor({wire::encode(tileJob(1, 0, kCausticTile, 4, kDirectAndCaustics))}),
            "tile of pass 4 needs a photon map this rank has not received");
}

TEST(SlaveHandlers, AMapNeverKeptIsAnError) {
  EXPECT_EQ(errorFor({wire::encode(wire::PhotonMapAgainMessage{3, 1})}),
            "pass 3 reuses the photon map of pass 1, which this rank does not keep");
}

TEST(SlaveHandlers, RadiiForAMapNeverReceivedAreAnError) {
  EXPECT_EQ(errorFor({wire::encode(wire::PhotonRadiiJobMessage{5, 0, 100})}),
            "radii job for the photon map of pass 5, which this rank has not received");
  EXPECT_EQ(errorFor({wire::encode(wire::PhotonRadiiMessage{5, {1.0f}})}),
            "radii for the photon map of pass 5, which this rank has not received");
}

// Messages a slave never receives (a slave's own kinds) are ignored: the session goes on.
TEST(SlaveHandlers, MessagesOnlyRankZeroReceivesAreIgnored) {
  SlaveUnderTest slave;
  slave.broadcast(test::smallScene());
  ASSERT_TRUE(slave.ready());
  slave.send(wire::encode(wire::ReadyMessage{0.1, 1}));
  slave.send(wire::encode(wire::ProgressMessage{1, 2, {}}));
  slave.send(wire::encode(wire::EchoMessage{1, ""}));
  ASSERT_TRUE(slave.next(Type::Echo));
  const std::vector<Type> end = slave.shutDown();
  EXPECT_EQ(std::count(end.begin(), end.end(), Type::Error), 0);
  EXPECT_EQ(slave.join().exitCode, 0);
}

}  // namespace
}  // namespace prism

// The ranks of a run find a photon map's radii together (master/frame/PhotonPass.h): each slave a
// share of the map's spatial order, rank 0 its own and a silent slave's, and every slave then
// gets every radius. Played here with a scripted slave over the loopback transport; the radii
// and rank 0's estimates must equal one rank's, bit for bit.
#include "master/frame/PhotonPass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <random>
#include <thread>

#include "HangGuard.h"
#include "caustics/GatherRadius.h"
#include "caustics/PhotonRadii.h"
#include "master/RealSlave.h"
#include "master/ScriptedSlave.h"
#include "master/SlowPath.h"
#include "parse/SceneLoader.h"
#include "transport/LoopbackTransport.h"

namespace prism {
namespace {

constexpr uint32_t kPass = 3;

// The glass ball's caustic: a few thousand stored photons, a fold and a focus among them.
struct CausticPhotons {
  CausticPhotons() : scene(loadScene(PRISM_SOURCE_DIR "/scenes/caustic-glass-sphere.yaml")) {
    const PhotonTracer tracer(scene, 20000, scene.causticSettings().maxBounces);
    WorkDispatcher alone(scene, nullptr, {});
    PhotonPassStats stats;
    photons = *tracePhotonPass(tracer, kPass, 2, alone, stats);
    map = std::make_shared<const PhotonMap>(photons);
    settings.k = 50;
    settings.radius = automaticMaxRadius(scene);
  }
  Scene scene;
  std::vector<Photon> photons;
  std::shared_ptr<const PhotonMap> map;
  PhotonGatherSettings settings;
};

// Rank 0's gather against one rank's: the same estimate at every 7th photon, bit for bit.
void expectSameEstimates(const PhotonGather& gather, const CausticPhotons& c) {
  const PhotonGather alone(c.map, c.settings, 1);
  int compared = 0;
  for (size_t i = 0; i < c.photons.size(); i += 7) {
    const Vec3 normal = -c.photons[i].directionVector();
    const Color got = gather.irradiance(c.photons[i].position, normal);
    const Color expected = alone.irradiance(c.photons[i].position, normal);
    ASSERT_EQ(got, expected) << "photon " << i;
    compared += got.x > 0.0f;
  }
  EXPECT_GT(compared, 100);
}

// The lease never runs out: a slave is retired by its silence or not at all.
DistributionOptions patientLink(double heartbeatTimeoutSeconds) {
  DistributionOptions o;
  o.threads = 1;
  o.leaseSeconds = test::kNeverSeconds;
  o.heartbeatTimeoutSeconds = heartbeatTimeoutSeconds;
  return o;
}

TEST(PhotonPass, ASlaveFindsItsShareOfTheRadiiAndGetsThemAll) {
  const CausticPhotons c;
  const std::vector<float> expected =
      photonRadii(*c.map, c.settings.k, c.settings.radius, c.settings.automaticK, 1);
  ASSERT_GT(c.photons.size(), 4 * kPhotonRadiiChunk);

  LoopbackNetwork network(2);
  ScriptedSlave slave(network.endpoint(1), c.scene);
  slave.ready(1);
  wire::PhotonRadiiJobMessage job;
  std::vector<float> received;
  std::thread script([&] {
    const auto mapMessage = slave.waitFor(wire::MessageType::PhotonMap);
    const auto jobMessage = slave.waitFor(wire::MessageType::PhotonRadiiJob);
    if (!mapMessage || !jobMessage) return;
    const PhotonMap its(wire::decode<wire::PhotonMapMessage>(*mapMessage).photons);
    job = wire::decode<wire::PhotonRadiiJobMessage>(*jobMessage);
    // A share of another pass first, with radii that would spoil the gather: ignored.
    slave.send(wire::encode(wire::PhotonRadiiShareMessage{job.pass + 1, job.first,
                                                          std::vector<float>(job.count, 9.0f)}));
    slave.send(wire::encode(wire::PhotonRadiiShareMessage{
        job.pass, job.first,
        photonRadiiShare(its, c.settings.k, c.settings.radius, c.settings.automaticK, job.first,
                         job.count, 1)}));
    if (const auto all = slave.waitFor(wire::MessageType::PhotonRadii)) {
      received = wire::decode<wire::PhotonRadiiMessage>(*all).radii;
    }
  });
  WorkDispatcher dispatcher(c.scene, &network.endpoint(0), patientLink(60.0));
  SlaveLink& link = dispatcher.link();
  link.receive(5.0);  // the slave's Ready
  PhotonPassStats stats;
  const auto gather = gatherFromPhotons(c.photons, kPass, c.settings, 1, dispatcher, stats);
  script.join();

  // Equal threads, equal shares (in whole chunks), the slave's second.
  EXPECT_EQ(job.pass, kPass);
  EXPECT_EQ(job.first % kPhotonRadiiChunk, 0u);
  EXPECT_GT(job.first, 0u);
  EXPECT_EQ(job.first + job.count, c.photons.size());
  ASSERT_EQ(stats.radiiByRank.size(), 2u);
  EXPECT_EQ(stats.radiiByRank[0], job.first);
  EXPECT_EQ(stats.radiiByRank[1], job.count);
  EXPECT_FALSE(link.retired(1));
  ASSERT_EQ(received.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) ASSERT_EQ(received[i], expected[i]) << i;
  ASSERT_NE(gather, nullptr);
  expectSameEstimates(*gather, c);
}

// A slave that takes its radii job and falls silent is retired after the heartbeat timeout, and
// rank 0 finds its share: the same gather.
TEST(PhotonPass, ASilentSlavesShareOfTheRadiiIsFoundByRankZero) {
  const CausticPhotons c;
  LoopbackNetwork network(2);
  ScriptedSlave slave(network.endpoint(1), c.scene);
  slave.ready(1);
  std::atomic<bool> stop{false};
  std::thread script([&] {
    slave.waitFor(wire::MessageType::PhotonRadiiJob);  // and never a word again
    while (!stop) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  });
  WorkDispatcher dispatcher(c.scene, &network.endpoint(0), patientLink(0.6));
  SlaveLink& link = dispatcher.link();
  link.receive(5.0);
  PhotonPassStats stats;
  const auto gather = test::unlessItHangs(
      [&] { return gatherFromPhotons(c.photons, kPass, c.settings, 1, dispatcher, stats); });
  stop = true;
  script.join();
  EXPECT_TRUE(link.retired(1));
  ASSERT_EQ(stats.radiiByRank.size(), 2u);
  EXPECT_EQ(stats.radiiByRank[0], c.photons.size());
  EXPECT_EQ(stats.radiiByRank[1], 0u);
  ASSERT_NE(gather, nullptr);
  expectSameEstimates(*gather, c);
}

// A fixed-radius gather needs no radii: the map goes out, and no radii job or radii follow.
TEST(PhotonPass, AFixedRadiusGatherSendsTheMapAlone) {
  CausticPhotons c;
  c.settings.fixedRadius = true;
  LoopbackNetwork network(2);
  ScriptedSlave slave(network.endpoint(1), c.scene);
  slave.ready(1);
  bool gotMap = false, gotRadiiMessage = false;
  std::thread script([&] {
    gotMap = slave.waitFor(wire::MessageType::PhotonMap).has_value();
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(300)) {
      const auto incoming = network.endpoint(1).waitForMessage(0.01);
      if (!incoming) continue;
      const wire::MessageType type = wire::decodeMessage(incoming->bytes).type;
      gotRadiiMessage = gotRadiiMessage || type == wire::MessageType::PhotonRadiiJob ||
                        type == wire::MessageType::PhotonRadii;
    }
  });
  WorkDispatcher dispatcher(c.scene, &network.endpoint(0), patientLink(60.0));
  SlaveLink& link = dispatcher.link();
  link.receive(5.0);
  PhotonPassStats stats;
  const auto gather = gatherFromPhotons(c.photons, kPass, c.settings, 1, dispatcher, stats);
  script.join();
  EXPECT_TRUE(gotMap);
  EXPECT_FALSE(gotRadiiMessage);
  EXPECT_TRUE(stats.radiiByRank.empty());
  ASSERT_NE(gather, nullptr);
  expectSameEstimates(*gather, c);
}

// A million photons scattered over a square, whose k = 400 radii (slowRadii) take seconds on
// one thread.
std::vector<Photon> manyPhotons() {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Photon> photons(1'000'000);
  for (Photon& p : photons) {
    p.position = Vec3(u(rng), 0.0f, u(rng));
    p.power = Color(1e-6f);
    p.setDirection(Vec3(0.0f, -1.0f, 0.0f));
  }
  return photons;
}

PhotonGatherSettings slowRadii() {
  PhotonGatherSettings settings;
  settings.k = 400;
  settings.radius = 0.5f;
  return settings;
}

// The camera moves while the ranks find the radii: rank 0 stops its share, tells the slave still
// finding its own to stop (PhotonCancel with the pass), and returns no gather, at once. The move
// comes when the slave has its share of the radii to find, not after a fixed wait: on a loaded
// machine building the photon map can outlast any such wait, and a pass dropped before its radii
// are handed out sends no PhotonCancel.
TEST(PhotonPass, ADroppedPassTellsTheSlavesFindingRadiiToStop) {
  const CausticPhotons c;  // for its scene
  LoopbackNetwork network(2);
  ScriptedSlave slave(network.endpoint(1), c.scene);
  slave.ready(1);
  std::atomic<bool> cancel{false};
  std::optional<uint32_t> cancelled;
  std::chrono::steady_clock::time_point movedAt;
  std::thread script([&] {
    if (!slave.waitFor(wire::MessageType::PhotonRadiiJob, 30.0)) return;  // and never answers
    movedAt = std::chrono::steady_clock::now();
    cancel = true;
    if (const auto message = slave.waitFor(wire::MessageType::PhotonCancel, 30.0)) {
      cancelled = wire::decode<wire::PhotonCancelMessage>(*message).pass;
    }
  });
  WorkDispatcher dispatcher(c.scene, &network.endpoint(0), patientLink(60.0));
  SlaveLink& link = dispatcher.link();
  link.receive(5.0);
  PhotonPassStats stats;
  const auto gather =
      gatherFromPhotons(manyPhotons(), kPass, slowRadii(), 1, dispatcher, stats, false, &cancel);
  const auto returnedAt = std::chrono::steady_clock::now();
  script.join();
  EXPECT_EQ(gather, nullptr);
  ASSERT_TRUE(cancelled.has_value());
  EXPECT_EQ(*cancelled, kPass);
  // Rank 0's half of the radii, timed here: the dropped pass returned in a fraction of it.
  const PhotonMap map(manyPhotons());
  const double rankZerosHalf =
      test::projectedRadiiSeconds(map, slowRadii().k, slowRadii().radius, 1) / 2;
  EXPECT_LT(std::chrono::duration<double>(returnedAt - movedAt).count(), rankZerosHalf / 4);
  EXPECT_FALSE(link.retired(1));
}

// A real slave told to drop the pass whose radii it is finding stops within a chunk of photons
// and sends nothing for it: its shutdown acknowledgement comes at once, not after the share's
// seconds (the slave finishes its photon work before it leaves).
TEST(PhotonPass, ARealSlaveStopsFindingTheRadiiOfADroppedPassAndSendsNothing) {
  const SceneDescription d = loadScene(PRISM_SOURCE_DIR "/scenes/caustic-glass-sphere.yaml");
  const std::vector<Photon> photons = manyPhotons();
  const PhotonGatherSettings settings = slowRadii();
  test::RealSlaveJob job(d);
  Transport& master = job.master();
  ASSERT_TRUE(job.ready());
  master.send(1, wire::encodePhotonMap(kPass, settings, photons));
  master.send(1, wire::encode(wire::PhotonRadiiJobMessage{kPass, 0, photons.size()}));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // map built, radii begun
  const test::CancelledPass c = test::cancelPassAndShutDown(master, kPass, 60.0);
  EXPECT_EQ(job.join(), 0);
  ASSERT_FALSE(c.seen.empty());
  EXPECT_EQ(c.seen.back(), wire::MessageType::Shutdown);
  EXPECT_EQ(std::count(c.seen.begin(), c.seen.end(), wire::MessageType::PhotonRadiiShare), 0);
  // The slave's whole share (every radius, on its one thread), timed here: the acknowledgement
  // came in a fraction of it.
  const PhotonMap map(photons);
  EXPECT_LT(c.seconds, test::projectedRadiiSeconds(map, settings.k, settings.radius, 1) / 4);
}

// The one photon-pass sequence (trace, then map, radii and discs) gives the gather the two
// halves give called one after the other, and counts the pass the same way.
TEST(PhotonPass, OnePassIsTheTraceThenTheGather) {
  const CausticPhotons c;
  const PhotonTracer tracer(c.scene, 20000, c.scene.causticSettings().maxBounces);
  WorkDispatcher alone(c.scene, nullptr, {});
  PhotonPassStats inOne;
  const auto gather = runPhotonPass(tracer, kPass, c.settings, 2, alone, inOne);
  PhotonPassStats inTwo;
  std::vector<Photon> photons = *tracePhotonPass(tracer, kPass, 2, alone, inTwo);
  const auto reference = gatherFromPhotons(std::move(photons), kPass, c.settings, 2, alone, inTwo);
  ASSERT_TRUE(gather);
  ASSERT_EQ(gather->map().size(), reference->map().size());
  EXPECT_EQ(std::memcmp(gather->map().photons().data(), reference->map().photons().data(),
                        gather->map().size() * sizeof(Photon)),
            0);
  EXPECT_EQ(inOne.trace.stored, gather->map().size());
  EXPECT_EQ(inOne.trace.emitted, inTwo.trace.emitted);
  EXPECT_EQ(inOne.mapBytes, inTwo.mapBytes);
  EXPECT_EQ(inOne.radiiByRank, inTwo.radiiByRank);
}

// A run's photon statistics are its passes added up: counts, times and bytes sent summed, the
// largest map's bytes kept, and the per-rank counts summed rank by rank.
TEST(PhotonPass, PassStatisticsAddUp) {
  PhotonPassStats first;
  first.trace.emitted = 1000;
  first.trace.stored = 300;
  first.traceSeconds = 0.5;
  first.buildSeconds = 0.25;
  first.distributeSeconds = 0.125;
  first.radiiSeconds = 0.0625;
  first.mapBytes = 4096;
  first.sentBytes = 2048;
  first.photonsByRank = {600, 400};
  first.radiiByRank = {300};
  PhotonPassStats second = first;
  second.trace.stored = 200;
  second.mapBytes = 1024;
  second.photonsByRank = {500, 300, 200};
  PhotonPassStats total = first;
  total += second;
  EXPECT_EQ(total.trace.emitted, 2000u);
  EXPECT_EQ(total.trace.stored, 500u);
  EXPECT_EQ(total.traceSeconds, 1.0);
  EXPECT_EQ(total.buildSeconds, 0.5);
  EXPECT_EQ(total.distributeSeconds, 0.25);
  EXPECT_EQ(total.radiiSeconds, 0.125);
  EXPECT_EQ(total.mapBytes, 4096u);
  EXPECT_EQ(total.sentBytes, 4096u);
  EXPECT_EQ(total.photonsByRank, (std::vector<uint64_t>{1100, 700, 200}));
  EXPECT_EQ(total.radiiByRank, (std::vector<uint64_t>{600}));
  EXPECT_EQ(total.photonsPerSecond(), 2000.0);
}

}  // namespace
}  // namespace prism

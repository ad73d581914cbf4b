// The master's side of the tile protocol, in one process: rank 0 renders frames through the one
// dispatcher (renderFrame) while slaves, played message by message over the loopback transport
// (ScriptedSlave.h) or real ones (runSlave on threads), answer late, twice, out of order, lose
// tiles, fall silent, freeze or vanish. The image must be bit-identical to one process's, and
// each failure must be handled by the mechanism the design names (a heartbeat, the silence, a
// failed send), not by the lease: those tests set the lease beyond the hang guard.
#include "master/dispatch/WorkDispatcher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <map>
#include <sstream>
#include <thread>

#include "HangGuard.h"
#include "master/RealSlave.h"
#include "master/ScriptedSlave.h"
#include "master/SlowPath.h"
#include "master/dispatch/SlaveShutdown.h"
#include "master/frame/CausticPasses.h"
#include "master/frame/FrameRenderer.h"
#include "master/frame/PhotonPass.h"
#include "master/frame/TilePlan.h"
#include "parse/SceneLoader.h"
#include "transport/LoopbackTransport.h"
#include "wire/GeometryCodec.h"
#include "wire/Messages.h"

namespace prism {
namespace {

SceneDescription smallScene() {
  SceneDescription d = loadScene(PRISM_SOURCE_DIR "/scenes/default.yaml");
  d.render.width = 64;
  d.render.height = 48;
  d.render.samplesPerPixel = 1;
  return d;
}

// A glass ball's caustic, small enough for a photon pass and a frame in a fraction of a second.
SceneDescription smallCausticScene() {
  SceneDescription d = loadScene(PRISM_SOURCE_DIR "/scenes/caustic-glass-sphere.yaml");
  d.render.width = 48;
  d.render.height = 36;
  d.render.samplesPerPixel = 1;
  d.caustics.photons = 20000;
  return d;
}

bool bitIdentical(const ImageRgb& a, const ImageRgb& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

// A two-rank job: the test thread is rank 0; rank 1 says Ready and then runs `script` on its own
// thread until it returns or the test says stop. Ready is queued before rank 0 starts, so rank 0's
// own render thread cannot finish a frame before the slave is known, however loaded the machine.
class TwoRanks {
 public:
  explicit TwoRanks(const Scene& scene) : network_(2), slave_(network_.endpoint(1), scene) {}
  ~TwoRanks() { join(); }

  template <typename Script>
  void start(Script script) {
    slave_.ready();
    thread_ = std::thread([this, script] { script(slave_, stop_); });
  }
  void join() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  Transport& master() { return network_.endpoint(0); }
  LoopbackNetwork& network() { return network_; }

 private:
  LoopbackNetwork network_;
  ScriptedSlave slave_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

FrameOptions options(bool masterRenders, double heartbeatTimeout, double lease) {
  FrameOptions o;
  o.distribution.threads = 1;
  o.distribution.tileSize = 16;  // 12 tiles
  o.distribution.heartbeatTimeoutSeconds = heartbeatTimeout;
  o.distribution.leaseSeconds = lease;
  o.masterRenders = masterRenders;
  o.frameId = 5;
  return o;
}

TEST(WorkDispatcher, LateDuplicateOutOfOrderAndOtherFrameResultsLeaveTheImageExact) {
  const Scene scene(smallScene());
  const FrameResult alone = renderFrame(scene, options(true, 2.0, 30.0));
  TwoRanks job(scene);
  job.start([](ScriptedSlave& s, std::atomic<bool>& stop) {
    while (!stop) {
      // Two jobs (the prefetch), answered in reverse order, each twice, and a copy tagged with
      // another frame.
      const auto a = s.nextJob(0.2);
      const auto b = a ? s.nextJob(0.2) : std::nullopt;
      for (const auto& job : {b, a}) {
        if (!job) continue;
        const wire::TileResultMessage tile = s.render(*job);
        s.deliver(tile);
        s.deliver(tile);
        wire::TileResultMessage other = tile;
        other.frame = tile.frame - 1;
        s.deliver(other);
      }
    }
  });
  WorkDispatcher dispatcher(scene, &job.master(), options(false, 2.0, 30.0).distribution);
  const FrameResult f = renderFrame(dispatcher, options(false, 2.0, 30.0));
  job.join();
  EXPECT_TRUE(bitIdentical(f.image, alone.image));
  EXPECT_EQ(f.workers[1].tiles, f.tileCount);  // only the slave rendered
  EXPECT_EQ(f.workers[0].tiles, 0u);
  // Every copy but the first is dropped; those of the last pair may come after the frame.
  EXPECT_GE(f.workers[1].staleTiles, 2 * (f.tileCount - 2));
  EXPECT_EQ(f.reissuedTiles, 0u);
  EXPECT_FALSE(f.workers[1].retired);
}

// The opening (rank 0's geometry broadcast in `prism render`) runs once, as the first frame
// begins: rank 0's render threads already take its tiles, and the slave finds the geometry
// waiting when its first job comes (its leases start after the broadcast).
TEST(WorkDispatcher, TheGeometryGoesOutAsTheFirstFrameBeginsBeforeTheSlavesFirstJobs) {
  const Scene scene(smallScene());
  const FrameResult alone = renderFrame(scene, options(true, 2.0, 30.0));
  TwoRanks job(scene);
  std::atomic<bool> hadJob{false}, geometryBeforeJob{false};
  std::vector<uint8_t> received;
  job.start([&](ScriptedSlave& s, std::atomic<bool>& stop) {
    while (!stop) {
      const auto next = s.nextJob(0.05);
      if (!next) continue;
      if (!hadJob.exchange(true)) {
        try {
          job.network().endpoint(1).broadcast(received, 0.0);  // already there, or it throws
          geometryBeforeJob = true;
        } catch (const TransportError&) {
        }
      }
      s.deliver(s.render(*next));
    }
  });
  WorkDispatcher dispatcher(scene, &job.master(), options(true, 2.0, 30.0).distribution);
  GeometrySharePlan record;
  dispatcher.sendGeometryAtOpening(record);
  EXPECT_TRUE(dispatcher.openingPending());
  const FrameResult f = renderFrame(dispatcher, options(true, 2.0, 30.0));
  job.join();
  EXPECT_FALSE(dispatcher.openingPending());
  EXPECT_TRUE(record.sentWhileRendering);  // rank 0's threads were rendering the frame
  EXPECT_TRUE(geometryBeforeJob);
  EXPECT_EQ(received, wire::encode(scene.geometry()));
  EXPECT_EQ(record.sentBytes, received.size());
  EXPECT_TRUE(bitIdentical(f.image, alone.image));
}

TEST(WorkDispatcher, ATileTheHeartbeatNamesLostIsReissuedAtOnce) {
  const Scene scene(smallScene());
  const FrameResult alone = renderFrame(scene, options(true, 2.0, 30.0));
  TwoRanks job(scene);
  job.start([](ScriptedSlave& s, std::atomic<bool>& stop) {
    bool lost = false;
    while (!stop) {
      const auto next = s.nextJob(0.2);
      if (!next) continue;
      if (!lost) {  // the first job vanishes (say a render thread died) and the heartbeat says so
        s.lose(next->tileIndex);
        s.heartbeat();
        lost = true;
        continue;
      }
      s.deliver(s.render(*next));
    }
  });
  // Lease and silence never run out: only the heartbeat can bring the tile back.
  const FrameOptions o = options(false, test::kNeverSeconds, test::kNeverSeconds);
  WorkDispatcher dispatcher(scene, &job.master(), o.distribution);
  const FrameResult f = test::unlessItHangs([&] { return renderFrame(dispatcher, o); });
  job.join();
  EXPECT_TRUE(bitIdentical(f.image, alone.image));
  EXPECT_EQ(f.workers[1].lostTiles, 1u);
  EXPECT_EQ(f.reissuedTiles, 1u);
  EXPECT_FALSE(f.workers[1].retired);
}

TEST(WorkDispatcher, ASilentSlaveIsRetiredAfterTheHeartbeatTimeoutNotTheLease) {
  const Scene scene(smallScene());
  const FrameResult alone = renderFrame(scene, options(true, 2.0, 30.0));
  TwoRanks job(scene);
  job.start([](ScriptedSlave& s, std::atomic<bool>& stop) {
    // Takes two jobs and dies: no result, no heartbeat.
    s.nextJob();
    s.nextJob();
    while (!stop) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  });
  // The lease never runs out: only the silence can retire the slave.
  const FrameOptions o = options(true, 0.6, test::kNeverSeconds);
  WorkDispatcher dispatcher(scene, &job.master(), o.distribution);
  const FrameResult f = test::unlessItHangs([&] { return renderFrame(dispatcher, o); });
  job.join();
  EXPECT_TRUE(bitIdentical(f.image, alone.image));
  EXPECT_TRUE(f.workers[1].retired);
  EXPECT_TRUE(dispatcher.link().retired(1));
  EXPECT_EQ(f.reissuedTiles, 2u);
}

TEST(WorkDispatcher, ASlaveThatHeartbeatsButNeverDeliversIsBoundedByTheLease) {
  const Scene scene(smallScene());
  const FrameResult alone = renderFrame(scene, options(true, 2.0, 30.0));
  TwoRanks job(scene);
  job.start([](ScriptedSlave& s, std::atomic<bool>& stop) {
    s.nextJob();
    s.nextJob();
    while (!stop) {  // frozen render threads, live message loop
      s.heartbeat();
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  WorkDispatcher dispatcher(scene, &job.master(), options(true, 0.6, 1.0).distribution);
  const FrameResult f = renderFrame(dispatcher, options(true, 0.6, 1.0));
  job.join();
  EXPECT_TRUE(bitIdentical(f.image, alone.image));
  EXPECT_TRUE(f.workers[1].retired);
  EXPECT_EQ(f.reissuedTiles, 2u);
  EXPECT_EQ(f.workers[1].lostTiles, 0u);  // it says it holds them: not lost, just stuck
}

TEST(WorkDispatcher, ASlaveTheTransportKnowsIsGoneIsRetiredAtTheFirstSend) {
  const Scene scene(smallScene());
  const FrameResult alone = renderFrame(scene, options(true, 2.0, 30.0));
  TwoRanks job(scene);
  job.network().disconnect(1);
  // Lease and silence never run out: only the failed send can retire the slave.
  const FrameOptions o = options(true, test::kNeverSeconds, test::kNeverSeconds);
  WorkDispatcher dispatcher(scene, &job.master(), o.distribution);
  const FrameResult f = test::unlessItHangs([&] { return renderFrame(dispatcher, o); });
  EXPECT_TRUE(bitIdentical(f.image, alone.image));
  EXPECT_TRUE(f.workers[1].retired);
  EXPECT_EQ(f.workers[0].tiles, f.tileCount);
}

// What the message list says only rank 0 sends, and a slave's own message out of its phase (a
// set-up Hello while frames run), each end the run naming the rank and the message.
TEST(WorkDispatcher, AnUnexpectedMessageNamesTheRank) {
  const Scene scene(smallScene());
  const std::pair<std::vector<uint8_t>, std::string> cases[] = {
      {wire::encode(wire::PhotonJobMessage{1, 0, 10, 10}),
       "rank 1 sent PhotonJob, which only rank 0 sends"},
      {wire::encode(wire::HelloMessage{maskOf(InstructionSet::Baseline), "a CPU"}),
       "rank 1 sent an unexpected Hello"},
  };
  for (const auto& [bytes, expected] : cases) {
    SCOPED_TRACE(expected);
    TwoRanks job(scene);
    job.start([bytes](ScriptedSlave& s, std::atomic<bool>&) { s.send(bytes); });
    WorkDispatcher dispatcher(scene, &job.master(), options(false, 60.0, 60.0).distribution);
    try {
      renderFrame(dispatcher, options(false, 60.0, 60.0));
      ADD_FAILURE() << "expected an error";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

// A slave retired during a photon pass (silent past the heartbeat timeout) that sends its share
// afterwards: rank 0 traced the share itself, the late one is ignored wherever it lands.
TEST(WorkDispatcher, APhotonShareAfterRetirementIsIgnored) {
  const SceneDescription d = smallCausticScene();
  const Scene scene(d);
  FrameOptions o = options(true, 0.6, 60.0);
  const CausticFrame alone = renderWithCaustics(scene, o);
  TwoRanks job(scene);
  job.start([](ScriptedSlave& s, std::atomic<bool>& stop) {
    // Takes its photon job without a word, and answers long after it was given up on.
    const auto photonJob = s.waitFor(wire::MessageType::PhotonJob);
    std::this_thread::sleep_for(std::chrono::milliseconds(1200));
    if (photonJob) {
      const wire::PhotonJobMessage asked = wire::decode<wire::PhotonJobMessage>(*photonJob);
      wire::PhotonShareMessage late{asked.pass, asked.first, asked.count, {}, 0.1, {}};
      late.photons.resize(static_cast<size_t>(asked.count));  // would spoil the image if used
      s.send(wire::encode(late));
    }
    while (!stop) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  });
  WorkDispatcher dispatcher(scene, &job.master(), o.distribution);
  const CausticFrame f = renderWithCaustics(dispatcher, o);
  job.join();
  EXPECT_TRUE(bitIdentical(f.image, alone.image));
  EXPECT_TRUE(dispatcher.link().retired(1));
}

// Real slaves (runSlave on threads) over the loopback: photon shares, the map broadcast and
// tiles, then the shutdown handshake; the same image as one process.
TEST(WorkDispatcher, RealSlavesOverTheLoopbackRenderTheSameCausticImage) {
  const SceneDescription d = smallCausticScene();
  const Scene scene(d);
  FrameOptions o = options(true, 2.0, 60.0);
  const CausticFrame alone = renderWithCaustics(scene, o);

  LoopbackNetwork network(3);
  std::vector<std::thread> slaves;
  std::vector<int> exitCodes(3, -1);
  for (int r = 1; r < 3; ++r) {
    slaves.push_back(test::startRealSlave(network, r, &exitCodes[static_cast<size_t>(r)]));
  }
  test::sendSceneAsRankZero(network, d);
  // Rank 0 renders no tiles here, so the slaves' share cannot depend on how fast they start.
  const FrameOptions distributed = options(false, 2.0, 60.0);
  WorkDispatcher dispatcher(scene, &network.endpoint(0), distributed.distribution);
  const CausticFrame f = renderWithCaustics(dispatcher, distributed);
  std::ostringstream err;
  EXPECT_EQ(shutDownSlaves(&network.endpoint(0), 0, dispatcher.link().retiredRanks(), err), 0)
      << err.str();
  for (std::thread& t : slaves) t.join();
  EXPECT_EQ(exitCodes[1], 0);
  EXPECT_EQ(exitCodes[2], 0);
  EXPECT_TRUE(bitIdentical(f.image, alone.image));
  EXPECT_EQ(f.caustics.photons.photonsByRank.size(), 3u);
  EXPECT_GT(f.caustics.photons.photonsByRank[1], 0u);
  ASSERT_EQ(f.caustics.photons.radiiByRank.size(), 3u);  // every rank found a share of the radii
  EXPECT_GT(f.caustics.photons.radiiByRank[1], 0u);
  EXPECT_GT(f.caustics.photons.radiiByRank[2], 0u);
  EXPECT_EQ(f.frames.workers[0].tiles, 0u);
  EXPECT_EQ(f.frames.workers[1].tiles + f.frames.workers[2].tiles, f.frames.tileCount);
}

// A camera move cancels rank 0's photon pass; a slave still tracing its share of it is told to
// stop (PhotonCancel) with the pass's number.
TEST(WorkDispatcher, ACancelledPhotonPassTellsTheSlavesStillTracingToStop) {
  const Scene scene(smallCausticScene());
  TwoRanks job(scene);
  std::atomic<bool> cancelReceived{false};
  uint32_t cancelledPass = 0;
  job.start([&](ScriptedSlave& s, std::atomic<bool>&) {
    if (!s.waitFor(wire::MessageType::PhotonJob)) return;  // takes its share and never answers
    if (const auto cancel = s.waitFor(wire::MessageType::PhotonCancel)) {
      cancelledPass = wire::decode<wire::PhotonCancelMessage>(*cancel).pass;
      cancelReceived = true;
    }
  });
  DistributionOptions o;
  o.threads = 1;
  o.leaseSeconds = 60.0;
  o.heartbeatTimeoutSeconds = 60.0;
  WorkDispatcher dispatcher(scene, &job.master(), o);
  SlaveLink& link = dispatcher.link();
  link.receive(5.0);  // the scripted slave's Ready (taken in by the link)
  ASSERT_TRUE(link.ready(1));
  // Rank 0's own share is large enough to be still running when the cancel comes.
  const PhotonTracer tracer(scene, 4'000'000, scene.causticSettings().maxBounces);
  std::atomic<bool> cancel{false};
  std::chrono::steady_clock::time_point cancelledAt;
  std::thread mover([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    cancelledAt = std::chrono::steady_clock::now();
    cancel = true;
  });
  PhotonPassStats stats;
  const std::optional<std::vector<Photon>> photons =
      tracePhotonPass(tracer, 7, 1, dispatcher, stats, &cancel);
  const auto returnedAt = std::chrono::steady_clock::now();
  mover.join();
  job.join();
  EXPECT_FALSE(photons.has_value());
  // Rank 0's share (half the pass, on one thread), timed here: the cancelled pass returned in a
  // fraction of it.
  const double rankZerosShare = test::projectedTraceSeconds(scene, tracer.photonsPerPass(), 1) / 2;
  EXPECT_LT(std::chrono::duration<double>(returnedAt - cancelledAt).count(), rankZerosShare / 4);
  EXPECT_TRUE(cancelReceived);
  EXPECT_EQ(cancelledPass, 7u);
}

// A real slave (runSlave on a thread) told to cancel the share it is tracing stops within a
// chunk of photons and sends nothing for it: its shutdown acknowledgement comes at once, not
// after the share's seconds of tracing (the slave finishes its photon work before it leaves).
TEST(WorkDispatcher, ARealSlaveStopsTracingACancelledShareAndSendsNothingForIt) {
  const SceneDescription d = smallCausticScene();
  test::RealSlaveJob job(d);
  Transport& master = job.master();
  ASSERT_TRUE(job.ready());
  // 20 M photons on one thread take about 10 s to trace (3.9 s for 8 M, measured).
  constexpr uint64_t kPhotons = 20'000'000;
  master.send(1, wire::encode(wire::PhotonJobMessage{3, 0, kPhotons, kPhotons}));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const test::CancelledPass c = test::cancelPassAndShutDown(master, 3, 20.0);
  EXPECT_EQ(job.join(), 0);
  ASSERT_FALSE(c.seen.empty());
  EXPECT_EQ(c.seen.back(), wire::MessageType::Shutdown);
  EXPECT_EQ(std::count(c.seen.begin(), c.seen.end(), wire::MessageType::PhotonShare), 0);
  // The whole share on the slave's one thread, timed here: the acknowledgement came in a
  // fraction of it.
  EXPECT_LT(c.seconds, test::projectedTraceSeconds(Scene(d), kPhotons, 1) / 4);
}

// A real slave rendering a tile of a frame that a View then ends (its liveFrom is later) stops
// the tile after its row and sends nothing for it: the next frame's tile comes at once, not
// after the ended tile's seconds.
TEST(WorkDispatcher, ARealSlaveStopsTheTileOfAFrameAViewEnds) {
  const SceneDescription d = smallScene();
  test::RealSlaveJob job(d);
  Transport& master = job.master();
  // The frames' tiles as they arrive (frame ids), until `frame` has sent one.
  std::vector<uint32_t> tilesOf;
  const auto waitForTileOf = [&](uint32_t frame, double seconds) {
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() <
           seconds) {
      const auto incoming = master.waitForMessage(0.05);
      if (!incoming) continue;
      const wire::Message message = wire::decodeMessage(incoming->bytes);
      if (message.type != wire::MessageType::TileResult) continue;
      tilesOf.push_back(wire::decode<wire::TileResultMessage>(message).frame);
      if (tilesOf.back() == frame) return true;
    }
    return false;
  };
  ASSERT_TRUE(job.ready());
  // Frame 1: the whole 64×48 image at 16384 spp as one tile, seconds of work on one thread.
  RenderView heavy{d.camera, d.render.width, d.render.height, 16384};
  master.send(1, wire::encode(wire::ViewMessage{1, 1, heavy}));
  master.send(1,
              wire::encode(wire::TileJobMessage{1, 0, {0, 0, d.render.width, d.render.height}, 0}));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  // Frame 2 ends frame 1 (liveFrom 2); its one small tile.
  RenderView light = heavy;
  light.samplesPerPixel = 1;
  master.send(1, wire::encode(wire::ViewMessage{2, 2, light}));
  const auto switched = std::chrono::steady_clock::now();
  master.send(1, wire::encode(wire::TileJobMessage{2, 0, {0, 0, 8, 8}, 0}));
  ASSERT_TRUE(waitForTileOf(2, 30.0));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - switched).count();
  master.send(1, wire::encode(wire::ShutdownMessage{}));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  waitForTileOf(1, 0.5);  // a frame-1 tile sent late would show here
  EXPECT_EQ(job.join(), 0);
  EXPECT_EQ(tilesOf, std::vector<uint32_t>{2});
  // The heavy tile's whole render on the slave's one thread, projected here from 1/64 of its
  // samples: frame 2's tile came in a fraction of it.
  SceneDescription sample = d;
  sample.render.samplesPerPixel = 16384 / 64;
  FrameOptions one;
  one.distribution.threads = 1;
  one.distribution.tileSize = std::max(d.render.width, d.render.height);
  const double heavyTile = 64 * test::secondsOf([&] { renderFrame(Scene(sample), one); });
  EXPECT_LT(seconds, heavyTile / 4);
}

class CountingListener : public FrameListener {
 public:
  void tileFinished(uint32_t frame, TileResult&&, int) override { ++finished_[frame]; }
  size_t finished(uint32_t frame) { return finished_[frame]; }  // only after the threads stop

 private:
  std::map<uint32_t, size_t> finished_;
};

// The viewer ends the frame of the view it leaves from the GUI thread while its coordinator may
// already have begun the next view's frame; ending the older frame late must leave the newer one
// running (before, it ended whatever frame was current and the viewer waited forever).
TEST(WorkDispatcher, EndingAnOlderFrameLateLeavesTheCurrentOneRunning) {
  const Scene scene(smallScene());
  DistributionOptions o;
  o.threads = 1;
  WorkDispatcher dispatcher(scene, nullptr, o);
  CountingListener listener;
  const std::vector<TileRect> tiles = planTiles(64, 48, 16);
  dispatcher.beginFrame({1, tiles, nullptr, nullptr, true, -1}, &listener);
  dispatcher.beginFrame({2, tiles, nullptr, nullptr, true, -1}, &listener);
  dispatcher.endFrame(1);
  dispatcher.startLocalWorkers();
  const auto start = std::chrono::steady_clock::now();
  while (!dispatcher.frameComplete() &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(20)) {
    dispatcher.service(0.05);
  }
  const bool complete = dispatcher.frameComplete();
  dispatcher.endFrame(2);  // the current frame: ends it
  EXPECT_FALSE(dispatcher.frameComplete());
  dispatcher.stop();
  dispatcher.join();
  EXPECT_TRUE(complete);
  EXPECT_EQ(listener.finished(2), tiles.size());
  EXPECT_EQ(listener.finished(1), 0u);
}

// Renders the dispatcher's frames on rank 0's threads until the current one is complete (20 s at
// most), then stops them.
void renderUntilComplete(WorkDispatcher& dispatcher) {
  dispatcher.startLocalWorkers();
  const auto start = std::chrono::steady_clock::now();
  while (!dispatcher.frameComplete() &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(20)) {
    dispatcher.service(0.05);
  }
  dispatcher.stop();
  dispatcher.join();
}

// The viewer's pipelined frames: a frame queued behind a running one is not ended; every tile of
// the older frame is handed out before any of the newer one's, and both complete.
class OrderListener : public FrameListener {
 public:
  void tileAssigned(uint32_t frame, uint32_t, int) override { order_.push_back(frame); }
  void tileFinished(uint32_t frame, TileResult&&, int) override { ++finished_[frame]; }
  // Only after the threads stop:
  const std::vector<uint32_t>& order() const { return order_; }
  size_t finished(uint32_t frame) { return finished_[frame]; }

 private:
  std::vector<uint32_t> order_;
  std::map<uint32_t, size_t> finished_;
};

TEST(WorkDispatcher, AQueuedFrameFollowsTheRunningOneWithoutEndingIt) {
  const Scene scene(smallScene());
  DistributionOptions o;
  o.threads = 2;
  WorkDispatcher dispatcher(scene, nullptr, o);
  OrderListener listener;
  const std::vector<TileRect> tiles = planTiles(64, 48, 16);
  dispatcher.queueFrame({1, tiles, nullptr, nullptr, true, -1}, &listener);
  dispatcher.queueFrame({2, tiles, nullptr, nullptr, true, -1}, &listener);
  renderUntilComplete(dispatcher);
  EXPECT_EQ(listener.finished(1), tiles.size());
  EXPECT_EQ(listener.finished(2), tiles.size());
  const std::vector<uint32_t>& order = listener.order();
  ASSERT_EQ(order.size(), 2 * tiles.size());
  EXPECT_TRUE(std::is_sorted(order.begin(), order.end())) << "a frame-2 tile before frame 1's last";
  EXPECT_EQ(dispatcher.stats()[0].staleTiles, 0u);
}

// beginFrame, unlike queueFrame, ends every frame before: none of the first frame's tiles is
// handed out once the second has begun.
TEST(WorkDispatcher, BeginningAFrameEndsAQueuedOne) {
  const Scene scene(smallScene());
  DistributionOptions o;
  o.threads = 1;
  WorkDispatcher dispatcher(scene, nullptr, o);
  OrderListener listener;
  const std::vector<TileRect> tiles = planTiles(64, 48, 16);
  dispatcher.queueFrame({1, tiles, nullptr, nullptr, true, -1}, &listener);
  dispatcher.beginFrame({2, tiles, nullptr, nullptr, true, -1}, &listener);
  renderUntilComplete(dispatcher);
  EXPECT_EQ(listener.finished(1), 0u);
  EXPECT_EQ(listener.finished(2), tiles.size());
}

// A listener may call the dispatcher from its calls, which come without the dispatcher's lock
// (with it held, as they once were, the first call below deadlocked): each call asks how many
// tiles are done, and the frame's last tile ends the frame, as the viewer ends a pass.
class CallingBackListener : public FrameListener {
 public:
  CallingBackListener(WorkDispatcher& dispatcher, size_t tiles)
      : dispatcher_(dispatcher), tiles_(tiles) {}
  void tileAssigned(uint32_t, uint32_t, int) override {
    assignedSeen_.push_back(dispatcher_.tilesDone());
  }
  void tileFinished(uint32_t frame, TileResult&&, int) override {
    doneSeen_.push_back(dispatcher_.tilesDone());
    if (doneSeen_.size() == tiles_) dispatcher_.endFrame(frame);
    ++finished_;
  }
  size_t finished() const { return finished_; }
  // Only after the threads stop:
  const std::vector<size_t>& assignedSeen() const { return assignedSeen_; }
  const std::vector<size_t>& doneSeen() const { return doneSeen_; }

 private:
  WorkDispatcher& dispatcher_;
  size_t tiles_;
  std::vector<size_t> assignedSeen_, doneSeen_;
  std::atomic<size_t> finished_{0};
};

TEST(WorkDispatcher, AListenerMayCallTheDispatcherFromItsCalls) {
  const Scene scene(smallScene());
  DistributionOptions o;
  o.threads = 2;
  WorkDispatcher dispatcher(scene, nullptr, o);
  const std::vector<TileRect> tiles = planTiles(64, 48, 16);
  CallingBackListener listener(dispatcher, tiles.size());
  dispatcher.beginFrame({1, tiles, nullptr, nullptr, true, -1}, &listener);
  dispatcher.startLocalWorkers();
  while (listener.finished() < tiles.size()) dispatcher.service(0.05);
  EXPECT_EQ(dispatcher.tilesDone(), 0u);  // the listener ended the frame
  dispatcher.stop();
  dispatcher.join();
  EXPECT_EQ(listener.assignedSeen().size(), tiles.size());
  const std::vector<size_t>& done = listener.doneSeen();
  ASSERT_EQ(done.size(), tiles.size());
  // A tile is counted done before it is told, and the calls come one at a time, in order.
  for (size_t i = 0; i < done.size(); ++i) EXPECT_GE(done[i], i + 1);
  EXPECT_TRUE(std::is_sorted(done.begin(), done.end()));
}

// Rank 0's threads are decided once, by the dispatcher (util/ThreadCount.h): the count the command
// line names, or every available core; a frame renders with them.
TEST(WorkDispatcher, DecidesRankZerosThreadsOnce) {
  const Scene scene(smallScene());
  WorkDispatcher unnamed(scene, nullptr, DistributionOptions{});
  EXPECT_EQ(unnamed.localThreads(), availableCores());
  DistributionOptions o;
  o.threads = 3;
  WorkDispatcher named(scene, nullptr, o);
  EXPECT_EQ(named.localThreads(), 3);
  FrameOptions frame;
  frame.distribution = o;
  EXPECT_EQ(renderFrame(named, frame).threads, 3);
}

}  // namespace
}  // namespace prism

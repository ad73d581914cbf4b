// A job serving its live session and viewers connecting to it, in one process over loopback
// TCP: the right viewer sees exactly what `prism render` makes; every bad connection is dropped
// while the job renders on and stays reachable for the right viewer.
#include "master/remote/ViewServer.h"

#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <sstream>
#include <thread>

#include "image/ToneMap.h"
#include "master/frame/CausticPasses.h"
#include "master/frame/FrameRenderer.h"
#include "master/live/DisplayFrame.h"
#include "master/live/LocalLiveSource.h"
#include "master/remote/ViewClient.h"
#include "parse/SceneLoader.h"

namespace prism {
namespace {

using Clock = std::chrono::steady_clock;

bool waitUntil(const std::function<bool()>& done, double seconds = 30.0) {
  const auto start = Clock::now();
  while (!done()) {
    if (std::chrono::duration<double>(Clock::now() - start).count() > seconds) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

SceneDescription smallScene(int width, int height) {
  SceneDescription d = loadScene(PRISM_SOURCE_DIR "/scenes/default.yaml");
  d.render.width = width;
  d.render.height = height;
  d.render.samplesPerPixel = 1;
  return d;
}

ServeOptions serveOptions() {
  ServeOptions o;
  o.address = "127.0.0.1:0";
  o.clientTimeoutSeconds = 2.0;
  o.helloTimeoutSeconds = 0.5;
  return o;
}

// The job: a live source on this process's threads, served.
class ServedJob {
 public:
  explicit ServedJob(ServeOptions options = serveOptions(), int width = 48, int height = 27)
      : description_(smallScene(width, height)),
        scene_(description_),
        source_(scene_, liveOptions(), description_, "default.yaml"),
        server_(source_, options, log_) {
    thread_ = std::thread([this] { reason_ = server_.run(); });
  }
  ~ServedJob() { finish(); }

  // Stops the job; returns the server's log.
  std::string finish() {
    if (thread_.joinable()) {
      server_.stop();
      thread_.join();
    }
    return log_.str();
  }
  // Waits for the job to end by itself.
  std::string join() {
    thread_.join();
    return reason_;
  }

  ConnectionInfo info() const { return {server_.endpoint(), server_.token(), view::kVersion}; }
  ConnectionInfo withToken(const std::string& token) const {
    ConnectionInfo i = info();
    i.token = token;
    return i;
  }
  const Scene& scene() const { return scene_; }
  const SceneDescription& description() const { return description_; }
  LocalLiveSource& source() { return source_; }
  ViewServer& server() { return server_; }

 private:
  static LiveOptions liveOptions() {
    LiveOptions o;
    o.distribution.threads = 1;
    o.maxPasses = 1 << 20;
    o.statsInterval = 0.05;
    return o;
  }

  std::ostringstream log_;  // written by the server's thread; read once it has ended
  SceneDescription description_;
  Scene scene_;
  LocalLiveSource source_;
  ViewServer server_;
  std::thread thread_;
  std::string reason_;
};

// A connected viewer: the client's run() on a thread, its news applied to a frame as a window
// would.
class Viewer {
 public:
  explicit Viewer(const ConnectionInfo& job)
      : client_(job), frame_(client_.start().width, client_.start().height) {
    thread_ = std::thread([this] {
      ended_ = client_.run([this](bool) {
        std::lock_guard lock(mutex_);
        woken_ = true;
        changed_.notify_all();
      });
      std::lock_guard lock(mutex_);
      done_ = true;
      changed_.notify_all();
    });
  }
  ~Viewer() { leave(); }
  void leave() {
    if (!thread_.joinable()) return;
    client_.stop();
    thread_.join();
  }
  // Takes news until done(frame) holds.
  bool waitFor(const std::function<bool(const DisplayFrame&)>& done, double seconds = 30.0) {
    const auto start = Clock::now();
    for (;;) {
      frame_.apply(client_.take());
      if (done(frame_)) return true;
      std::unique_lock lock(mutex_);
      if (done_ || std::chrono::duration<double>(Clock::now() - start).count() > seconds) {
        return false;
      }
      changed_.wait_for(lock, std::chrono::milliseconds(20), [&] { return woken_; });
      woken_ = false;
    }
  }
  // Waits for run() to return by itself; returns why it ended.
  std::string waitForEnd(double seconds = 30.0) {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, std::chrono::duration<double>(seconds), [&] { return done_; });
    return done_ ? ended_ : "still running";
  }

  ViewClient& client() { return client_; }
  const DisplayFrame& frame() const { return frame_; }

 private:
  ViewClient client_;
  DisplayFrame frame_;
  std::mutex mutex_;
  std::condition_variable changed_;
  bool woken_ = false;
  bool done_ = false;
  std::string ended_;
  std::thread thread_;
};

std::string refusalOf(const ConnectionInfo& job) {
  try {
    ViewClient client(job);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "welcomed";
}

// A raw connection: sends bytes, then reads what comes back until the job closes it (or 10 s).
std::vector<view::Message> sendRaw(const ConnectionInfo& job, const std::vector<uint8_t>& bytes,
                                   bool* closed = nullptr) {
  Socket s = connectTcp(job.endpoint, 5.0);
  if (!bytes.empty()) sendAll(s, bytes, 5.0);
  MessageReader reader(view::kServerToClient);
  std::vector<view::Message> got;
  const auto start = Clock::now();
  bool open = true;
  while (open && std::chrono::duration<double>(Clock::now() - start).count() < 10.0) {
    pollfd p{s.fd(), POLLIN, 0};
    ::poll(&p, 1, 50);
    open = reader.readFrom(s, got);
  }
  if (closed) *closed = !open;
  return got;
}

std::string reasonIn(const std::vector<view::Message>& messages) {
  if (messages.size() != 1 || messages[0].type != view::MessageType::Refused) return "no refusal";
  return view::decode<view::RefusedMessage>(messages[0]).reason;
}

TEST(ViewServer, TheViewerSeesWhatRenderMakesAndSavesItsFullPrecision) {
  ServedJob job;
  Viewer viewer(job.info());
  EXPECT_EQ(viewer.client().start().sceneName,
            "default.yaml · job at " + job.info().endpoint.text());
  EXPECT_EQ(viewer.client().start().width, 48);
  EXPECT_TRUE(viewer.client().start().resume);  // the job rendered before anyone came
  ViewSettings view = viewer.client().start().view;
  view.tag = 77;
  view.maxPasses = 1;  // pass 1 is exactly `prism render`'s image
  viewer.client().setView(view);
  ASSERT_TRUE(viewer.waitFor([](const DisplayFrame& f) {
    return f.pass().viewTag == 77 && f.state().fullPassesDone == 1 && f.passComplete();
  }));
  const ImageRgb expected = renderWithCaustics(job.scene(), FrameOptions{}).image;
  const ImageRgb full = viewer.client().fullImage();
  ASSERT_EQ(full.pixels.size(), expected.pixels.size());
  for (size_t i = 0; i < full.pixels.size(); ++i) {
    ASSERT_EQ(full.pixels[i], expected.pixels[i]) << "pixel " << i;
  }
  ASSERT_TRUE(viewer.waitFor([&](const DisplayFrame& f) {
    const DisplayEncoder encode(job.description().render.exposure);
    for (size_t i = 0; i < expected.pixels.size(); ++i) {
      const Color& c = expected.pixels[i];
      if (f.bytes()[3 * i] != encode(c.r) || f.bytes()[3 * i + 1] != encode(c.g) ||
          f.bytes()[3 * i + 2] != encode(c.b)) {
        return false;
      }
    }
    return true;
  })) << "the display bytes are not the render's";
  EXPECT_GT(viewer.client().bytesReceived(), 0u);
  viewer.leave();
  const std::string log = job.finish();
  EXPECT_NE(log.find("connected"), std::string::npos) << log;
  EXPECT_NE(log.find("left: it said goodbye"), std::string::npos) << log;
}

TEST(ViewServer, AWrongOrMissingTokenIsRefusedAndTheRightViewerStillGetsIn) {
  ServedJob job;
  std::string wrong = job.info().token;
  wrong[10] = wrong[10] == 'a' ? 'b' : 'a';
  EXPECT_EQ(refusalOf(job.withToken(wrong)), "the job refused the connection: wrong token");
  EXPECT_EQ(refusalOf(job.withToken("")), "the job refused the connection: wrong token");
  EXPECT_EQ(refusalOf(job.info()), "welcomed");
  EXPECT_EQ(job.server().refused(), 2u);
}

TEST(ViewServer, GarbageOtherVersionsAndOversizedLengthsAreRefused) {
  ServedJob job;
  const std::string http = "GET / HTTP/1.1\r\nHost: x\r\n\r\n";
  EXPECT_EQ(reasonIn(sendRaw(job.info(), std::vector<uint8_t>(http.begin(), http.end()))),
            "not a Prism viewer message (it does not start with PRSV)");
  std::vector<uint8_t> hello = view::encode(view::HelloMessage{job.info().token, "test"});
  std::vector<uint8_t> newer = hello;
  newer[4] = static_cast<uint8_t>(view::kVersion + 1);
  const std::string speaks = ", this Prism speaks version " + std::to_string(view::kVersion) +
                             ": use the same Prism release on both sides";
  EXPECT_EQ(reasonIn(sendRaw(job.info(), newer)),
            "protocol version " + std::to_string(view::kVersion + 1) + speaks);
  std::vector<uint8_t> older = hello;
  older[4] = static_cast<uint8_t>(view::kVersion - 1);
  EXPECT_EQ(reasonIn(sendRaw(job.info(), older)),
            "protocol version " + std::to_string(view::kVersion - 1) + speaks);
  std::vector<uint8_t> huge(hello.begin(), hello.begin() + view::kHeaderSize);
  for (int i = 0; i < 8; ++i) huge[8 + i] = i == 4 ? 1 : 0;  // 4 GiB of Hello
  EXPECT_EQ(reasonIn(sendRaw(job.info(), huge)), "Hello of 4294967296 bytes, the limit is 4096");
  // The right token behind another first message is no way in.
  EXPECT_EQ(reasonIn(sendRaw(job.info(), view::encode(view::PingMessage{}))),
            "the first message must be Hello");
  EXPECT_EQ(refusalOf(job.info()), "welcomed");
}

TEST(ViewServer, AHalfOpenConnectionIsDroppedAndOthersGetInMeanwhile) {
  ServedJob job;
  Socket silent = connectTcp(job.info().endpoint, 5.0);  // connects, never says a word
  EXPECT_EQ(refusalOf(job.info()), "welcomed");
  MessageReader reader(view::kServerToClient);
  std::vector<view::Message> got;
  bool open = true;
  ASSERT_TRUE(waitUntil(
      [&] {
        open = reader.readFrom(silent, got);
        return !open;
      },
      10.0));
  EXPECT_EQ(reasonIn(got), "no token within the time allowed");
}

TEST(ViewServer, ASecondViewerIsRefusedWithAClearMessage) {
  ServedJob job;
  ConnectOptions named;
  Viewer first(job.info());
  const std::string refusal = refusalOf(job.info());
  EXPECT_EQ(refusal.rfind("the job refused the connection: another viewer (", 0), 0u) << refusal;
  EXPECT_NE(refusal.find("is connected to this job; it serves one at a time"), std::string::npos);
  first.leave();
  EXPECT_TRUE(waitUntil([&] { return refusalOf(job.info()) == "welcomed"; }, 10.0));
}

TEST(ViewServer, AViewerThatComesBackFindsTheAccumulatedPasses) {
  ServedJob job;
  std::vector<uint8_t> shown;
  {
    Viewer viewer(job.info());
    ViewSettings view = viewer.client().start().view;
    view.tag = 5;
    view.maxPasses = 3;
    viewer.client().setView(view);
    ASSERT_TRUE(viewer.waitFor([](const DisplayFrame& f) {
      return f.pass().viewTag == 5 && f.state().fullPassesDone == 3 && f.passComplete();
    }));
    shown = viewer.frame().bytes();
  }
  ASSERT_TRUE(waitUntil(
      [&] {
        try {
          Viewer back(job.info());
          EXPECT_TRUE(back.client().start().resume);
          EXPECT_EQ(back.client().start().view.tag, 5u);
          EXPECT_TRUE(back.waitFor(
              [&](const DisplayFrame& f) {
                return f.state().fullPassesDone == 3 && f.bytes() == shown;
              },
              10.0))
              << back.frame().state().fullPassesDone << " passes shown";
          return true;
        } catch (const std::runtime_error&) {
          return false;  // the job has not noticed the first one leave yet
        }
      },
      10.0));
}

TEST(ViewServer, AViewerKilledMidFrameIsDroppedAndTheNextGetsIn) {
  ServedJob job;
  {
    Socket s = connectTcp(job.info().endpoint, 5.0);
    sendAll(s, view::encode(view::HelloMessage{job.info().token, "killed"}), 5.0);
    uint8_t part[100];
    ASSERT_TRUE(waitUntil([&] { return ::recv(s.fd(), part, sizeof part, 0) > 0; }, 10.0));
  }  // closed with a frame half read: the job sees a reset
  EXPECT_TRUE(waitUntil([&] { return refusalOf(job.info()) == "welcomed"; }, 10.0));
  const std::string log = job.finish();
  EXPECT_NE(log.find("viewer     killed left"), std::string::npos) << log;
}

TEST(ViewServer, AViewerThatStopsReadingIsDroppedWhileTheJobRendersOn) {
  ServeOptions options = serveOptions();
  options.clientTimeoutSeconds = 1.0;
  ServedJob job(options, 192, 108);
  Socket s(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0));
  const int small = 4096;  // a window that fills at once
  ::setsockopt(s.fd(), SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
  s = connectTcp(job.info().endpoint, 5.0);
  ::setsockopt(s.fd(), SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
  sendAll(s, view::encode(view::HelloMessage{job.info().token, "stalled"}), 5.0);
  std::atomic<bool> pinging{true};
  std::thread pinger([&] {  // alive, but never reads (so never acknowledges news either)
    while (pinging) {
      try {
        sendAll(s, view::encode(view::PingMessage{}), 1.0);
      } catch (const std::exception&) {
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  const uint32_t frameBefore = job.source().stats().frame;
  EXPECT_TRUE(waitUntil([&] { return refusalOf(job.info()) == "welcomed"; }, 30.0));
  pinging = false;
  pinger.join();
  EXPECT_GT(job.source().stats().frame, frameBefore);  // the job rendered on meanwhile
  const std::string log = job.finish();
  EXPECT_NE(log.find("stalled left: it stopped reading"), std::string::npos) << log;
}

// News is not queued for a viewer: while two are unacknowledged the job sends nothing more,
// however many frames it renders; the news waits merged on its board.
TEST(ViewServer, AtMostTwoNewsAreInFlightUntilTheViewerAcknowledges) {
  ServedJob job;
  Socket s = connectTcp(job.info().endpoint, 5.0);
  sendAll(s, view::encode(view::HelloMessage{job.info().token, "slow"}), 5.0);
  MessageReader reader(view::kServerToClient);
  std::vector<view::Message> got;
  const auto news = [&] {
    size_t n = 0;
    for (const view::Message& m : got) n += m.type == view::MessageType::News;
    return n;
  };
  ASSERT_TRUE(waitUntil(
      [&] {
        reader.readFrom(s, got);
        return news() == 2;
      },
      10.0));
  const uint32_t frame = job.source().stats().frame;
  ASSERT_TRUE(waitUntil(
      [&] {
        sendAll(s, view::encode(view::PingMessage{}), 1.0);  // alive
        reader.readFrom(s, got);
        return job.source().stats().frame > frame + 5;  // the job rendered on meanwhile
      },
      10.0));
  EXPECT_EQ(news(), 2u);
  // Acknowledged: the newest news comes, one message however much happened.
  sendAll(s, view::encode(view::NewsReceivedMessage{2}), 1.0);
  ASSERT_TRUE(waitUntil(
      [&] {
        reader.readFrom(s, got);
        return news() >= 3;
      },
      10.0));
  const DisplayNews latest = view::decode<DisplayNews>(got.back());
  EXPECT_GT(latest.pass.frame, frame);
}

// A viewer asking for the full-precision image again and again gets the latest request
// answered, not a queue of images (each is 12 bytes a pixel).
TEST(ViewServer, FullImageRequestsDoNotQueueImages) {
  ServedJob job;
  Socket s = connectTcp(job.info().endpoint, 5.0);
  std::vector<uint8_t> burst = view::encode(view::HelloMessage{job.info().token, "greedy"});
  for (uint32_t i = 1; i <= 1000; ++i) {
    const std::vector<uint8_t> request = view::encode(view::FullImageRequestMessage{i});
    burst.insert(burst.end(), request.begin(), request.end());
  }
  sendAll(s, burst, 5.0);
  MessageReader reader(view::kServerToClient);
  std::vector<view::Message> got;
  std::vector<uint32_t> answered;
  ASSERT_TRUE(waitUntil(
      [&] {
        got.clear();
        reader.readFrom(s, got);
        for (const view::Message& m : got) {
          if (m.type == view::MessageType::FullImage) {
            answered.push_back(view::decode<view::FullImageMessage>(m).request);
          } else if (m.type == view::MessageType::News) {
            sendAll(s, view::encode(view::NewsReceivedMessage{0}), 1.0);  // stays a viewer
          }
        }
        return !answered.empty() && answered.back() == 1000;
      },
      10.0));
  EXPECT_LE(answered.size(), 5u);  // one per batch of requests the job read, not 1000
}

TEST(ViewServer, AHundredConnectionAttemptsInASecondLeaveTheJobReachable) {
  ServedJob job;
  for (int i = 0; i < 100; ++i) {
    Socket s = connectTcp(job.info().endpoint, 5.0);
    const uint8_t junk[8] = {1, 2, 3, 4, 5, 6, 7, static_cast<uint8_t>(i)};
    ::send(s.fd(), junk, sizeof junk, MSG_NOSIGNAL);
  }
  EXPECT_EQ(refusalOf(job.info()), "welcomed");
  EXPECT_TRUE(waitUntil([&] { return job.server().refused() >= 100; }, 20.0))
      << job.server().refused();
}

TEST(ViewServer, TheViewerHearsThatTheJobEnded) {
  ServedJob job;
  Viewer viewer(job.info());
  job.server().stop();
  EXPECT_EQ(viewer.waitForEnd(), "the job ended: the job was stopped");
}

TEST(ViewServer, TheViewerHearsThatTheConnectionWasLost) {
  // A job killed outright says nothing: its side of the connection just closes.
  Endpoint bound;
  Socket listener = listenTcp(parseEndpoint("127.0.0.1:0"), &bound);
  std::thread fakeJob([&] {
    Socket s;
    waitUntil([&] { return (s = acceptConnection(listener)).valid(); });
    MessageReader reader(view::kClientToServer);
    std::vector<view::Message> got;
    waitUntil([&] {
      reader.readFrom(s, got);
      return !got.empty();
    });
    ViewerStart start;
    start.sceneName = "x";
    start.width = start.height = 4;
    sendAll(s, view::encode(view::WelcomeMessage{start}), 5.0);
  });  // and closes
  Viewer viewer({bound, std::string(64, 'a'), view::kVersion});
  fakeJob.join();
  EXPECT_EQ(viewer.waitForEnd(), "the connection to the job was lost");
}

TEST(ViewServer, ExitWithClientEndsTheJobWhenTheViewerLeaves) {
  ServeOptions options = serveOptions();
  options.exitWithClient = true;
  ServedJob job(options);
  {
    Viewer viewer(job.info());
    ASSERT_TRUE(viewer.waitFor([](const DisplayFrame& f) { return f.state().started; }));
  }
  EXPECT_EQ(job.join(), "the viewer left (--exit-with-client)");
}

TEST(ViewServer, ListeningBeyondLoopbackMustBeAskedFor) {
  const SceneDescription d = smallScene(8, 8);
  const Scene scene(d);
  LocalLiveSource source(scene, LiveOptions{}, d, "x");
  ServeOptions options;
  options.address = "0.0.0.0:0";
  std::ostringstream log;
  try {
    ViewServer server(source, options, log);
    FAIL() << "listened beyond loopback unasked";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("add --allow-network to mean it"), std::string::npos)
        << e.what();
  }
  options.allowNetwork = true;
  ViewServer server(source, options, log);
  EXPECT_GT(server.endpoint().port, 0);
}

}  // namespace
}  // namespace prism

// The window against the real renderer: LocalLiveSource on its own coordinator thread, news
// taken on the source's wake-ups, as `prism view` runs it.
#include "gui/MainWindow.h"

#include <gtest/gtest.h>

#include <QApplication>
#include <QCheckBox>
#include <QElapsedTimer>
#include <QLabel>
#include <QRadioButton>
#include <QScreen>
#include <QScrollArea>
#include <QScrollBar>
#include <QSpinBox>
#include <QStatusBar>
#include <QTableWidget>
#include <QTest>
#include <QtCharts/QLineSeries>
#include <QtCharts/QScatterSeries>
#include <functional>
#include <thread>

#include "gui/FrameView.h"
#include "gui/ScriptedSource.h"
#include "gui/StatsPanel.h"
#include "image/ToneMap.h"
#include "master/frame/CausticPasses.h"
#include "master/frame/FrameRenderer.h"
#include "master/frame/ResourceCheck.h"
#include "master/live/LocalLiveSource.h"
#include "parse/SceneLoader.h"
#include "util/InstructionSet.h"

namespace prism {
namespace {

bool waitUntil(const std::function<bool()>& done, int milliseconds = 20000) {
  QElapsedTimer timer;
  timer.start();
  while (!done()) {
    if (timer.elapsed() > milliseconds) return false;
    QApplication::processEvents(QEventLoop::AllEvents, 5);
  }
  return true;
}

class LiveWindow {
 public:
  // memoryLimit: what caustic maps switched on must fit in (runViewer's is --memory-limit).
  LiveWindow(const std::string& scenePath, int width, int height, int spp, int maxPasses = 3,
             const MemoryLimit& memoryLimit = {})
      : description_(load(scenePath, width, height, spp)),
        scene_(description_),
        source_(scene_, options(maxPasses, memoryLimit), description_, "test"),
        window_(source_) {
    coordinator_ = std::thread([this] {
      source_.run(
          [this](bool) { QMetaObject::invokeMethod(&window_, "takeNews", Qt::QueuedConnection); });
    });
    window_.show();
    window_.startRendering();
  }
  ~LiveWindow() {
    source_.stop();
    coordinator_.join();
  }

  MainWindow& window() { return window_; }
  LiveRenderer& renderer() { return source_.renderer(); }
  LocalLiveSource& source() { return source_; }
  const Scene& scene() const { return scene_; }
  const SceneDescription& description() const { return description_; }

  bool waitForFullPasses(int passes) {
    return waitUntil([&] { return window_.fullPassesDone() >= passes; });
  }

 private:
  static SceneDescription load(const std::string& path, int width, int height, int spp) {
    SceneDescription d = loadScene(path);
    d.render.width = width;
    d.render.height = height;
    d.render.samplesPerPixel = spp;
    return d;
  }
  static LiveOptions options(int maxPasses, const MemoryLimit& memoryLimit) {
    LiveOptions o;
    o.memoryLimit = memoryLimit;
    o.distribution.threads = 2;
    o.previewScale = 4;
    o.maxPasses = maxPasses;
    o.statsInterval = 0.05;
    return o;
  }

  SceneDescription description_;
  Scene scene_;
  LocalLiveSource source_;
  MainWindow window_;
  std::thread coordinator_;
};

const std::string kDefaultScene = PRISM_SOURCE_DIR "/scenes/default.yaml";
const std::string kPlaneScene = PRISM_SOURCE_DIR "/scenes/lambert-plane.yaml";

TEST(MainWindow, ShowsTheFrameTheRendererProduced) {
  LiveWindow live(kDefaultScene, 96, 54, 2, 1);  // one full pass, then still
  ASSERT_TRUE(live.waitForFullPasses(1));
  // Pass 1 uses the scene's seed and spp: exactly the image `prism render` makes, the default
  // scene's caustic map included.
  const ImageRgb shown = live.source().fullImage();
  const ImageRgb expected = renderWithCaustics(live.scene(), FrameOptions{}).image;
  ASSERT_NE(expected.pixels, renderFrame(live.scene(), FrameOptions{}).image.pixels)
      << "the default scene's caustic is missing";
  ASSERT_EQ(shown.pixels.size(), expected.pixels.size());
  for (size_t i = 0; i < shown.pixels.size(); ++i) {
    ASSERT_EQ(shown.pixels[i], expected.pixels[i]) << "pixel " << i;
  }
  // The window's frame holds them as display bytes.
  const DisplayEncoder encode(live.description().render.exposure);
  const std::vector<uint8_t>& bytes = live.window().frame().bytes();
  for (size_t i = 0; i < expected.pixels.size(); ++i) {
    const Color& c = expected.pixels[i];
    ASSERT_EQ(bytes[3 * i], encode(c.r)) << "pixel " << i;
    ASSERT_EQ(bytes[3 * i + 1], encode(c.g)) << "pixel " << i;
    ASSERT_EQ(bytes[3 * i + 2], encode(c.b)) << "pixel " << i;
  }

  // The widget, at the image's size and without outlines, shows those pixels tone-mapped.
  FrameView* view = live.window().frameView();
  view->setShowTiles(false);
  view->setFixedSize(96, 54);
  ASSERT_TRUE(waitUntil([&] { return view->size() == QSize(96, 54); }));
  QTest::qWait(60);  // a repaint tick
  const QImage grabbed = view->grab().toImage().convertToFormat(QImage::Format_RGB888);
  ASSERT_EQ(grabbed.size(), QSize(96, 54));
  int mismatches = 0;
  for (int y = 0; y < 54; ++y) {
    for (int x = 0; x < 96; ++x) {
      const Color& c = expected.at(x, y);
      const QColor got = grabbed.pixelColor(x, y);
      if (got.red() != encode(c.r) || got.green() != encode(c.g) || got.blue() != encode(c.b)) {
        ++mismatches;
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(MainWindow, KeysMoveTheCameraAndStartANewFrame) {
  LiveWindow live(kDefaultScene, 64, 36, 1);
  ASSERT_TRUE(live.waitForFullPasses(1));
  MainWindow& w = live.window();
  const uint32_t frameBefore = w.frame().frame();
  const uint64_t viewBefore = w.viewId();
  const CameraDesc home = live.description().camera;
  const Vec3 forward = glm::normalize(home.lookAt - home.position);
  const float step = CameraController::kMoveFraction * glm::length(home.lookAt - home.position);

  QTest::keyClick(w.frameView(), Qt::Key_W, Qt::NoModifier, 0);
  const Vec3 moved = w.viewSettings().camera.position - home.position;
  EXPECT_NEAR(glm::length(moved - step * forward), 0.0f, 1e-4f);
  ASSERT_TRUE(waitUntil([&] { return w.viewId() == viewBefore + 1; }));
  EXPECT_GT(w.frame().frame(), frameBefore);
  EXPECT_EQ(w.frame().pass().camera.position, w.viewSettings().camera.position);

  QTest::keyClick(w.frameView(), Qt::Key_Left);  // turns: the look-at point moves
  EXPECT_NE(w.viewSettings().camera.lookAt, home.lookAt + step * forward);
  QTest::keyClick(w.frameView(), Qt::Key_R, Qt::NoModifier);  // 'r': back home
  EXPECT_EQ(w.viewSettings().camera.position, home.position);
  EXPECT_EQ(w.viewSettings().camera.lookAt, home.lookAt);
  // Views asked for faster than passes start are coalesced: the renderer goes to the latest.
  ASSERT_TRUE(waitUntil([&] {
    return w.viewId() > viewBefore + 1 && w.frame().pass().camera.lookAt == home.lookAt;
  }));

  QTest::keyClicks(w.frameView(), "h");
  EXPECT_TRUE(w.frameView()->showHelp());
  QTest::keyClick(w.frameView(), Qt::Key_Escape);
  EXPECT_FALSE(w.frameView()->showHelp());
  QTest::keyClicks(w.frameView(), "q");
  EXPECT_FALSE(w.isVisible());
}

TEST(MainWindow, NormalsViewShowsTheNormalAndBack) {
  LiveWindow live(kPlaneScene, 16, 16, 1);
  MainWindow& w = live.window();
  ASSERT_TRUE(live.waitForFullPasses(1));
  QTest::keyClicks(w.frameView(), "N");
  EXPECT_EQ(w.viewSettings().debugView, DebugView::Normals);
  const uint64_t normalsView = w.viewId() + 1;
  ASSERT_TRUE(waitUntil([&] { return w.viewId() == normalsView && w.frame().passComplete(); }));
  // Every pixel sees the plane y = 0 from above: normal (0, 1, 0) shows as (0.5, 1, 0.5).
  for (const Color& c : live.source().fullImage().pixels) ASSERT_EQ(c, Color(0.5f, 1.0f, 0.5f));
  const DisplayEncoder encode(live.description().render.exposure);
  const std::vector<uint8_t>& bytes = w.frame().bytes();
  for (size_t i = 0; i < bytes.size(); i += 3) {
    ASSERT_EQ(bytes[i], encode(0.5f));
    ASSERT_EQ(bytes[i + 1], encode(1.0f));
    ASSERT_EQ(bytes[i + 2], encode(0.5f));
  }
  QTest::keyClicks(w.frameView(), "n");
  EXPECT_EQ(w.viewSettings().debugView, DebugView::Image);
}

TEST(MainWindow, OpensWithinTheScreenAndAtThePreferredSizeWhereItFits) {
  const SceneDescription d = loadScene(kPlaneScene);
  ScriptedSource source(d);
  MainWindow window(source);
  const QScreen* screen = window.screen();
  ASSERT_NE(screen, nullptr);
  const QRect area = screen->availableGeometry();
  // Wider and taller than the screen (the offscreen platform's is 800x600): fitted, centred.
  window.fitToScreen(area.size() * 2);
  window.show();
  QApplication::processEvents();
  EXPECT_LE(window.width(), area.width());
  EXPECT_LE(window.height(), area.height());
  EXPECT_TRUE(area.contains(window.geometry()))
      << window.geometry().x() << "," << window.geometry().y();
  // What fits is taken as asked.
  const QSize small = window.minimumSizeHint().expandedTo(QSize(720, 480));
  ASSERT_LE(small.width(), area.width());
  window.fitToScreen(small);
  QApplication::processEvents();
  EXPECT_EQ(window.size(), small);
}

// The side panel scrolls up and down, never sideways: on a 1280x800 screen the window opens
// 1228 pixels wide, and the statistics' longest lines (a caustic map of a large view, a 1080p
// frame rate with four-digit frame counts) still fit beside the frame.
TEST(MainWindow, TheSidePanelFitsWithoutScrollingSideways) {
  const SceneDescription d = loadScene(kPlaneScene);
  ScriptedSource source(d);
  MainWindow window(source);
  window.resize(1228, 720);
  window.show();
  LiveStats s;
  s.frame = 123456;
  s.viewId = 4321;
  s.pass = 1024;
  s.passesDone = 1023;
  s.raysPerSecond = 123.4e6;
  s.frameTimes.medianSeconds = 1.2345;
  s.frameTimes.p95Seconds = 2.3456;
  s.frameTimeTargetSeconds = 0.0333;
  s.frameTimes.framesPerSecond = 123.4;
  s.frameTimes.shownWidth = 1920;
  s.frameTimes.shownHeight = 1080;
  s.frameTimes.fullResolutionFrames = 12345;
  s.frameTimes.reducedFrames = 67890;
  s.lastPassSeconds = 1.2345;
  s.lastPassBusySeconds = 123.45;
  s.totalThreads = 128;
  s.photons.method = CausticMethod::CausticMap;
  s.photons.mapResolution = 2048;
  s.photons.mapViews = 6;
  s.photons.mapBlur = true;
  s.photons.mapBuildSeconds = 1.2345;
  s.ranks.resize(2);
  const auto* scroll = window.findChild<QScrollArea*>("sidePanel");
  ASSERT_NE(scroll, nullptr);
  const auto showAndCheck = [&] {
    window.statsPanel()->showStats(s);
    QApplication::processEvents();
    EXPECT_EQ(scroll->horizontalScrollBar()->maximum(), 0)
        << "panel " << scroll->widget()->width() << " px in a viewport of "
        << scroll->viewport()->width() << " px";
  };
  showAndCheck();
  // Photon mapping's lines, as long as they get.
  s.photons.method = CausticMethod::PhotonMap;
  s.photons.photonsPerPass = 10000000;
  s.photons.passes = 1234;
  s.photons.last.trace.stored = 12345678;
  s.photons.last.trace.emitted = 152337300;  // 123.4 M photons/s
  s.photons.last.mapBytes = 1234u << 20;
  s.photons.last.traceSeconds = 1.2345;
  s.photons.last.buildSeconds = 0.2345;
  s.photons.last.distributeSeconds = 0.1234;
  s.photons.radius = 0.012345f;
  showAndCheck();
}

// News the window has not taken yet is merged: one take shows the pixels of every patch posted
// and hears of every pass completed meanwhile, in order.
TEST(MainWindow, NewsPostedBeforeATakeIsMergedIntoOne) {
  const SceneDescription d = loadScene(kPlaneScene);
  ScriptedSource source(d);
  MainWindow w(source);
  std::vector<int> completed;
  QObject::connect(&w, &MainWindow::passComplete,
                   [&](const DisplayPass& pass) { completed.push_back(pass.pass); });
  int fullPasses = 0;
  QObject::connect(&w, &MainWindow::fullPassDone, [&](int passes) { fullPasses = passes; });
  w.startRendering();
  ASSERT_EQ(source.requested.size(), 1u);
  const uint64_t tag = source.requested[0].tag;
  for (int pass = 1; pass <= 2; ++pass) {
    DisplayNews news;
    news.started = true;
    news.width = d.render.width;
    news.height = d.render.height;
    news.pass.viewId = 1;
    news.pass.viewTag = tag;
    news.pass.pass = pass;
    news.pass.tiles = 1;
    news.tilesDone = 1;
    news.fullPassesDone = pass;
    news.completed = {news.pass};
    news.patch = {pass - 1, 0, 1, 1};  // pixel (0, 0), then (1, 0)
    news.patchBytes = {static_cast<uint8_t>(10 * pass), 0, 0};
    source.post(news);
  }
  w.takeNews();
  const std::vector<uint8_t>& bytes = w.frame().bytes();
  EXPECT_EQ(bytes[0], 10);
  EXPECT_EQ(bytes[3], 20);
  EXPECT_EQ(completed, (std::vector<int>{1, 2}));
  EXPECT_EQ(fullPasses, 2);
  EXPECT_EQ(w.frame().pass().pass, 2);
  EXPECT_EQ(source.requested.size(), 1u);  // taking asked for no view

  DisplayNews wrongSize;
  wrongSize.width = d.render.width + 1;
  wrongSize.height = d.render.height;
  EXPECT_THROW(source.post(wrongSize), std::invalid_argument);
}

TEST(MainWindow, StatsPanelReceivesPerRankNumbers) {
  LiveWindow live(kDefaultScene, 64, 36, 1);
  ASSERT_TRUE(live.waitForFullPasses(2));
  const QTableWidget* table = live.window().statsPanel()->rankTable();
  ASSERT_TRUE(waitUntil([&] {
    return table->rowCount() == 1 && table->item(0, 2) && table->item(0, 2)->text().toInt() > 0;
  }));
  EXPECT_EQ(table->item(0, 0)->text(), "0");
  EXPECT_EQ(table->item(0, 1)->text(), "2");  // threads

  // Known numbers in, the same numbers out, one row per rank, and the chart's live point.
  LiveStats s;
  s.ranks.resize(3);
  for (int r = 0; r < 3; ++r) {
    s.ranks[r].rank = r;
    s.ranks[r].threads = 2;
    s.ranks[r].tiles = static_cast<size_t>(10 * (r + 1));
    s.ranks[r].busySeconds = 0.5 * (r + 1);
    s.ranks[r].rays.primary = 1500000ull * (r + 1);
  }
  s.ranks[2].retired = true;
  s.lastPassSeconds = 0.5;
  s.lastPassBusySeconds = 2.0;
  s.totalThreads = 4;
  StatsPanel panel;
  panel.setInstructionSet("x86-64-v3");
  panel.showStats(s);
  ASSERT_EQ(panel.rankTable()->rowCount(), 3);
  EXPECT_EQ(panel.rankTable()->item(1, 2)->text(), "20");
  EXPECT_EQ(panel.rankTable()->item(1, 3)->text(), "1.00");
  EXPECT_EQ(panel.rankTable()->item(2, 4)->text(), "4.50");
  EXPECT_EQ(panel.rankTable()->item(2, 0)->text(), "2 (retired)");
  ASSERT_EQ(panel.liveSpeedup()->count(), 1);
  EXPECT_EQ(panel.liveSpeedup()->at(0), QPointF(4.0, 4.0));  // 2 thread-s in 0.5 s on 4 threads
  EXPECT_TRUE(panel.summaryText().contains("efficiency 1.00"));
  EXPECT_TRUE(panel.summaryText().contains("kernels      x86-64-v3\n"));

  panel.setSpeedupTable({{1, 4.0, 1.0, 1.0}, {2, 2.5, 1.6, 0.8}}, "x.csv");
  ASSERT_EQ(panel.csvSpeedup()->count(), 2);
  EXPECT_EQ(panel.csvSpeedup()->at(1), QPointF(2.0, 1.6));
  EXPECT_EQ(panel.csvEfficiency()->at(1), QPointF(2.0, 0.8));
}

TEST(MainWindow, CausticsSwitchAndPhotonBudgetStartNewViewsAndPhotonStatsShow) {
  LiveWindow live(PRISM_SOURCE_DIR "/tests/data/scenes/caustic-small.yaml", 40, 30, 1, 2);
  MainWindow& w = live.window();
  auto* none = w.findChild<QRadioButton*>("causticsNone");
  auto* photonMap = w.findChild<QRadioButton*>("causticsPhotonMap");
  auto* photons = w.findChild<QSpinBox*>("photonsPerPass");
  ASSERT_TRUE(none && photonMap && photons);
  // The scene asks for photon mapping with 20000 photons: the panel starts there.
  EXPECT_TRUE(photonMap->isChecked());
  EXPECT_EQ(photons->value(), 20000);
  EXPECT_EQ(w.viewSettings().caustics, CausticMethod::PhotonMap);
  ASSERT_TRUE(live.waitForFullPasses(1));
  EXPECT_EQ(w.frame().pass().caustics, CausticMethod::PhotonMap);
  ASSERT_TRUE(waitUntil([&] {
    return w.statsPanel()->summaryText().contains("photons/s (20000 per pass)");
  })) << w.statsPanel()->summaryText().toStdString();
  // The job's kernels: with one process, the best this CPU runs.
  const QString kernels = QString("kernels      ") +
                          instructionSetName(bestInstructionSet(runnableInstructionSets())) + "\n";
  EXPECT_TRUE(w.statsPanel()->summaryText().contains(kernels))
      << w.statsPanel()->summaryText().toStdString();

  const uint64_t view = w.viewId();
  const uint32_t frame = w.frame().frame();
  none->click();
  EXPECT_EQ(w.viewSettings().caustics, CausticMethod::None);
  ASSERT_TRUE(waitUntil([&] { return w.viewId() == view + 1; }));
  EXPECT_GT(w.frame().frame(), frame);
  ASSERT_TRUE(live.waitForFullPasses(1));
  EXPECT_EQ(w.frame().pass().caustics, CausticMethod::None);
  ASSERT_TRUE(waitUntil([&] { return !w.statsPanel()->summaryText().contains("photons/s"); }));

  photons->setValue(5000);  // without photon mapping: nothing to re-render
  EXPECT_EQ(w.viewSettings().photonsPerPass, 5000u);
  QApplication::processEvents();
  EXPECT_EQ(w.viewId(), view + 1);
  photonMap->click();
  ASSERT_TRUE(waitUntil([&] { return w.viewId() == view + 2; }));
  ASSERT_TRUE(waitUntil([&] {
    return w.statsPanel()->summaryText().contains("photons/s (5000 per pass)");
  })) << w.statsPanel()->summaryText().toStdString();
  photons->setValue(6000);  // with it: a new view
  ASSERT_TRUE(waitUntil([&] { return w.viewId() == view + 3; }));

  // Known photon numbers in, the same numbers out.
  LiveStats s;
  s.photons.method = CausticMethod::PhotonMap;
  s.photons.photonsPerPass = 200000;
  s.photons.passes = 3;
  s.photons.last.trace.stored = 12345;
  s.photons.last.trace.emitted = 200000;  // in 0.25 s: 800 k photons/s
  s.photons.last.mapBytes = 3u << 20;
  s.photons.last.traceSeconds = 0.25;
  s.photons.last.buildSeconds = 0.0125;
  s.photons.radius = 0.0625f;
  StatsPanel panel;
  panel.showStats(s);
  const QString text = panel.summaryText();
  EXPECT_TRUE(text.contains("800.0 kphotons/s (200000 per pass)")) << text.toStdString();
  EXPECT_TRUE(text.contains("12345 photons, map " + QString::fromStdString(formatBytes(3 << 20))))
      << text.toStdString();
  EXPECT_TRUE(text.contains("passes       3 of this view")) << text.toStdString();
  EXPECT_TRUE(text.contains("trace 250.0 ms, kd-tree 12.5 ms")) << text.toStdString();
  EXPECT_TRUE(text.contains("gather r     0.0625")) << text.toStdString();
  s.photons.noCasters = true;
  panel.showStats(s);
  EXPECT_TRUE(panel.summaryText().contains("no light reaches a caustic caster"));
}

// Caustic mapping from the side panel and the keys: the switch and `b` start new views whose
// passes carry the maps' caustics, the statistics say which maps are in use, and R, P and C show
// exactly the light-space images of the maps the renderer built, until n.
TEST(MainWindow, CausticMapSwitchBlurKeyAndLightSpaceViews) {
  LiveWindow live(PRISM_SOURCE_DIR "/tests/data/scenes/caustic-small.yaml", 40, 30, 1, 2);
  MainWindow& w = live.window();
  auto* causticMap = w.findChild<QRadioButton*>("causticsCausticMap");
  auto* blur = w.findChild<QCheckBox*>("causticMapBlur");
  ASSERT_TRUE(causticMap && blur);
  EXPECT_TRUE(blur->isChecked());
  ASSERT_TRUE(live.waitForFullPasses(1));
  const uint64_t view = w.viewId();
  causticMap->click();
  EXPECT_EQ(w.viewSettings().caustics, CausticMethod::CausticMap);
  ASSERT_TRUE(waitUntil([&] { return w.viewId() == view + 1; }));
  ASSERT_TRUE(live.waitForFullPasses(1));
  EXPECT_EQ(w.frame().pass().caustics, CausticMethod::CausticMap);
  ASSERT_TRUE(waitUntil([&] {
    return w.statsPanel()->summaryText().contains("caustic map  512x512 x 1 view(s), blur on");
  })) << w.statsPanel()->summaryText().toStdString();

  QTest::keyClicks(w.frameView(), "b");
  EXPECT_FALSE(w.viewSettings().causticMapBlur);
  EXPECT_FALSE(blur->isChecked());
  ASSERT_TRUE(waitUntil([&] { return w.viewId() == view + 2; }));
  ASSERT_TRUE(waitUntil([&] { return w.statsPanel()->summaryText().contains("blur off"); }))
      << w.statsPanel()->summaryText().toStdString();

  const auto unblurred = live.renderer().causticMaps(false);
  ASSERT_FALSE(unblurred->empty());
  const struct {
    const char* key;
    LightSpaceMap map;
    const char* button;
  } views[] = {{"C", LightSpaceMap::Caustics, "debugCausticMap"},
               {"R", LightSpaceMap::Casters, "debugCasters"},
               {"P", LightSpaceMap::Receivers, "debugReceivers"}};
  for (const auto& v : views) {
    QTest::keyClicks(w.frameView(), v.key);
    ASSERT_TRUE(waitUntil([&] { return !w.frameView()->overlayImage().isNull(); }));
    EXPECT_EQ(w.lightSpaceShown(), v.map);
    EXPECT_TRUE(w.findChild<QRadioButton*>(v.button)->isChecked());
    const QImage expected = lightSpaceImage(*unblurred, v.map);
    EXPECT_EQ(w.frameView()->overlayImage(), expected);
    int lit = 0;  // texels with something to show
    for (int y = 0; y < expected.height(); ++y) {
      for (int x = 0; x < expected.width(); ++x) lit += expected.pixel(x, y) != qRgb(0, 0, 0);
    }
    EXPECT_GT(lit, 100);
    EXPECT_TRUE(w.frameView()->overlayCaption().contains("blur off"));
  }
  EXPECT_TRUE(w.frameView()->overlayCaption().startsWith("receiver positions (P)"));
  QTest::keyClicks(w.frameView(), "n");
  EXPECT_FALSE(w.frameView()->showsOverlay());
  EXPECT_FALSE(w.lightSpaceShown().has_value());
  EXPECT_EQ(w.viewSettings().debugView, DebugView::Image);
  EXPECT_EQ(w.viewId(), view + 2);  // leaving a light-space view re-renders nothing
}

// Caustic maps that would not fit in memory (the scene uses photon maps; LiveRenderer::
// causticMapsRefusal) cannot be switched on: the switch and the light-space views are disabled
// with the reason, choosing them anyway keeps the method and says why, and no new view starts.
TEST(MainWindow, CausticMapsThatCannotFitAreRefusedWithTheReason) {
  LiveWindow live(PRISM_SOURCE_DIR "/tests/data/scenes/caustic-small.yaml", 40, 30, 1, 2,
                  MemoryLimit{1 << 20, "test"});
  MainWindow& w = live.window();
  ASSERT_TRUE(live.renderer().causticMapsRefusal());
  auto* causticMap = w.findChild<QRadioButton*>("causticsCausticMap");
  auto* photonMap = w.findChild<QRadioButton*>("causticsPhotonMap");
  auto* irradiance = w.findChild<QRadioButton*>("debugCausticMap");
  ASSERT_TRUE(causticMap && photonMap && irradiance);
  const QString why = "caustic maps of 1 light at 512 texels a side (1 view) needs";
  EXPECT_FALSE(causticMap->isEnabled());
  EXPECT_FALSE(irradiance->isEnabled());
  EXPECT_TRUE(causticMap->toolTip().contains(why)) << causticMap->toolTip().toStdString();
  ASSERT_TRUE(live.waitForFullPasses(1));
  const uint64_t view = w.viewId();

  w.setCausticMethod(CausticMethod::CausticMap);
  EXPECT_EQ(w.viewSettings().caustics, CausticMethod::PhotonMap);
  EXPECT_TRUE(photonMap->isChecked());
  EXPECT_FALSE(causticMap->isChecked());
  EXPECT_TRUE(w.statusBar()->currentMessage().startsWith("caustic maps refused: " + why))
      << w.statusBar()->currentMessage().toStdString();
  QTest::keyClicks(w.frameView(), "C");
  EXPECT_TRUE(w.frameView()->overlayCaption().startsWith("caustic maps refused: " + why))
      << w.frameView()->overlayCaption().toStdString();
  QTest::keyClicks(w.frameView(), "n");
  EXPECT_FALSE(w.frameView()->showsOverlay());
  QApplication::processEvents();
  EXPECT_EQ(w.viewId(), view);  // nothing was re-rendered
}

// Over a connection the light-space images cannot be made: their buttons are disabled with the
// reason, and the keys show it instead of an image.
TEST(MainWindow, LightSpaceViewsASourceCannotGiveAreDisabledWithTheReason) {
  const SceneDescription d = loadScene(kPlaneScene);
  ScriptedSource source(d, "shown only beside the job");
  MainWindow w(source);
  auto* irradiance = w.findChild<QRadioButton*>("debugCausticMap");
  ASSERT_NE(irradiance, nullptr);
  EXPECT_FALSE(irradiance->isEnabled());
  EXPECT_TRUE(irradiance->toolTip().contains("shown only beside the job"));
  QTest::keyClicks(w.frameView(), "C");
  EXPECT_TRUE(w.frameView()->overlayCaption().startsWith("shown only beside the job"))
      << w.frameView()->overlayCaption().toStdString();
  EXPECT_TRUE(w.frameView()->overlayImage().isNull());
}

// A source that ends by itself (the job ended, the connection went): the window says why in
// its title and status bar and keeps the last frame.
TEST(MainWindow, SaysWhenItsSourceEnded) {
  const SceneDescription d = loadScene(kPlaneScene);
  ScriptedSource source(d);
  MainWindow w(source);
  w.sourceEnded("the job ended: the job was interrupted (SIGTERM)");
  EXPECT_TRUE(w.windowTitle().endsWith("(ended)")) << w.windowTitle().toStdString();
  bool said = false;
  for (const QLabel* label : w.statusBar()->findChildren<QLabel*>()) {
    said = said || label->text().startsWith("the job ended: the job was interrupted (SIGTERM)");
  }
  EXPECT_TRUE(said);
  EXPECT_EQ(w.endedBecause(), "the job ended: the job was interrupted (SIGTERM)");
}

TEST(MainWindow, SpeedupCsvErrorsAreReported) {
  SceneDescription d = loadScene(kPlaneScene);
  ScriptedSource source(d);
  MainWindow w(source);
  EXPECT_TRUE(w.loadSpeedupCsv("/no/such.csv").contains("cannot open"));
  EXPECT_TRUE(w.loadSpeedupCsv(PRISM_SOURCE_DIR "/docs/speedup-default.csv").isEmpty());
  EXPECT_EQ(w.statsPanel()->csvSpeedup()->count(), 2);
}

}  // namespace
}  // namespace prism

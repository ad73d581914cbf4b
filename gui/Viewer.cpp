#include "gui/Viewer.h"

#include <QApplication>
#include <QFileInfo>
#include <QKeyEvent>
#include <QTimer>
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <exception>
#include <optional>
#include <ostream>
#include <thread>
#include <vector>

#include "gui/FrameView.h"
#include "gui/MainWindow.h"
#include "gui/RenderBridge.h"
#include "gui/StatsPanel.h"
#include "image/ImageIo.h"
#include "util/Stopwatch.h"

namespace prism {
namespace {

// Qt aborts the process when it cannot reach a display; say so first, and clearly.
bool haveDisplay() {
  for (const char* variable : {"QT_QPA_PLATFORM", "DISPLAY", "WAYLAND_DISPLAY"}) {
    const char* value = std::getenv(variable);
    if (value && *value) return true;
  }
  return false;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// --benchmark-moves: orbits the camera as soon as the previous move's preview has been
// painted, and times each move from the request to that paint.
class MoveBenchmark : public QObject {
 public:
  MoveBenchmark(MainWindow& window, int moves, std::ostream& out)
      : window_(window), moves_(moves), out_(out) {
    connect(window.frameView(), &FrameView::painted, this, &MoveBenchmark::onPainted);
  }

 private:
  void move() {
    window_.cameraController().orbit(2.0f, 0.0f);  // like a 5-pixel mouse drag
    moveStart_ = SteadyClock::now();
    window_.viewChanged();
    waitingView_ = window_.viewId() + 1;
  }

  void onPainted(uint64_t viewId, int completedPass) {
    if (!started_) {
      if (completedPass >= 1) {  // the first full image is on screen: start moving
        started_ = true;
        runStart_ = SteadyClock::now();
        move();
      }
      return;
    }
    if (done_ || viewId != waitingView_ || completedPass < 0) return;
    if (latencies_.size() < static_cast<size_t>(moves_)) {
      latencies_.push_back(secondsSince(moveStart_));
      if (latencies_.size() < static_cast<size_t>(moves_)) {
        move();
        return;
      }
      movingSeconds_ = secondsSince(runStart_);
      fullStart_ = moveStart_;
      waitingFull_ = true;
    }
    if (waitingFull_ && completedPass >= 1) {
      done_ = true;
      const double full = secondsSince(fullStart_);
      const double fps = static_cast<double>(latencies_.size()) / movingSeconds_;
      out_ << "benchmark  " << latencies_.size() << " camera moves\n"
           << "preview    median " << 1e3 * median(latencies_) << " ms, max "
           << 1e3 * *std::max_element(latencies_.begin(), latencies_.end())
           << " ms (move to preview painted)\n"
           << "rate       " << fps << " previews/s while moving\n"
           << "full res   " << 1e3 * full << " ms after the last move (first full pass painted)\n";
      out_.flush();
      QTimer::singleShot(0, &window_, &QWidget::close);
    }
  }

  MainWindow& window_;
  int moves_;
  std::ostream& out_;
  bool started_ = false;
  bool done_ = false;
  bool waitingFull_ = false;
  uint64_t waitingView_ = 0;
  SteadyClock::time_point moveStart_, runStart_, fullStart_;
  std::vector<double> latencies_;
  double movingSeconds_ = 0.0;
};

void printSummary(const LiveStats& s, std::ostream& out) {
  out << "viewer     " << s.passesDone << " full passes of the last view, frame " << s.frame
      << "\n";
  const PhotonLiveStats& p = s.photons;
  if (p.method == CausticMethod::PhotonMap && p.passes > 0) {
    out << "photons    " << p.passes << " passes of " << p.photonsPerPass
        << ", the last: " << p.stored << " stored, trace " << 1e3 * p.traceSeconds << " ms ("
        << p.photonsPerSecond << " photons/s), kd-tree " << 1e3 * p.buildSeconds << " ms, send "
        << 1e3 * p.distributeSeconds << " ms, gather radius " << p.radius << "\n";
  }
  if (p.method == CausticMethod::CausticMap && p.mapResolution > 0) {
    out << "caustic map " << p.mapResolution << "x" << p.mapResolution << " x " << p.mapViews
        << " view(s), blur " << (p.mapBlur ? "on" : "off") << ", built on rank 0 in "
        << 1e3 * p.mapBuildSeconds << " ms\n";
  }
  for (const RankStats& r : s.ranks) {
    out << "rank " << r.rank << "     " << r.threads << " threads, " << r.tiles << " tiles, busy "
        << r.busySeconds << " thread-s, " << r.rays.total() << " rays, " << r.staleTiles
        << " stale tiles dropped" << (r.retired ? ", retired" : "") << "\n";
  }
}

}  // namespace

int runViewer(const Scene& scene, const SceneDescription& description, const ViewOptions& options,
              Transport* session, std::ostream& out, std::ostream& err) {
  if (!haveDisplay()) {
    err << "prism: error: no display: set DISPLAY (or run under xvfb-run), or set "
           "QT_QPA_PLATFORM=offscreen to render without a window\n";
    return 1;
  }
  static int argc = 1;
  static char name[] = "prism";
  static char* argv[] = {name, nullptr};
  QApplication app(argc, argv);

  LiveOptions live;
  live.distribution = options.render.distribution;
  live.previewScale = options.previewScale;
  live.maxPasses = options.maxPasses;
  LiveRenderer renderer(scene, live, session);
  RenderBridge bridge;
  MainWindow window(
      description, QFileInfo(QString::fromStdString(options.render.scenePath)).fileName(),
      [&renderer](const ViewSettings& v) { renderer.setView(v); },
      [&renderer](bool blur) { return renderer.causticMaps(blur); });
  // Queued: the bridge emits on the coordinator thread, the window lives on this one.
  QObject::connect(&bridge, &RenderBridge::passStartedSignal, &window, &MainWindow::onPassStarted,
                   Qt::QueuedConnection);
  QObject::connect(&bridge, &RenderBridge::tileAssignedSignal, &window, &MainWindow::onTileAssigned,
                   Qt::QueuedConnection);
  QObject::connect(&bridge, &RenderBridge::tileFinishedSignal, &window, &MainWindow::onTileFinished,
                   Qt::QueuedConnection);
  QObject::connect(&bridge, &RenderBridge::passFinishedSignal, &window, &MainWindow::onPassFinished,
                   Qt::QueuedConnection);
  QObject::connect(&bridge, &RenderBridge::statsUpdatedSignal, &window, &MainWindow::onStats,
                   Qt::QueuedConnection);

  if (!options.speedupCsv.empty()) {
    const QString error = window.loadSpeedupCsv(QString::fromStdString(options.speedupCsv));
    if (!error.isEmpty()) {
      err << "prism: error: " << error.toStdString() << "\n";
      return 1;
    }
  }
  // Kept at the moment the viewer decides to quit: tiles of the next pass may still be
  // delivered before the event loop ends.
  std::optional<ImageRgb> finalImage;
  if (options.exitAfterPasses > 0) {
    QObject::connect(&window, &MainWindow::fullPassDone, &window, [&](int passes) {
      if (finalImage || window.viewId() != 1 || passes < options.exitAfterPasses) return;
      finalImage = window.frame().image();
      renderer.stop();
      window.close();
    });
  }
  if (!options.screenshotPath.empty()) {
    QTimer::singleShot(static_cast<int>(options.screenshotSeconds * 1000), &window, [&] {
      if (!window.grab().save(QString::fromStdString(options.screenshotPath))) {
        err << "prism: error: cannot write " << options.screenshotPath << "\n";
      }
      window.close();
    });
  }
  for (const char c : options.keys) {  // queued: handled once the event loop runs, in order
    const int key = std::isalpha(static_cast<unsigned char>(c))
                        ? Qt::Key_A + (std::toupper(static_cast<unsigned char>(c)) - 'A')
                        : static_cast<int>(c);
    const Qt::KeyboardModifiers shift =
        std::isupper(static_cast<unsigned char>(c)) ? Qt::ShiftModifier : Qt::NoModifier;
    QCoreApplication::postEvent(&window,
                                new QKeyEvent(QEvent::KeyPress, key, shift, QString(QChar(c))));
  }
  std::unique_ptr<MoveBenchmark> benchmark;
  if (options.benchmarkMoves > 0) {
    benchmark = std::make_unique<MoveBenchmark>(window, options.benchmarkMoves, out);
  }

  std::exception_ptr failure;
  std::thread coordinator([&] {
    try {
      renderer.run(bridge);
    } catch (...) {
      failure = std::current_exception();
      QMetaObject::invokeMethod(&app, "quit", Qt::QueuedConnection);
    }
  });
  window.fitToScreen(QSize(1600, 900));
  window.show();
  window.startRendering();
  app.exec();
  renderer.stop();
  coordinator.join();
  if (failure) std::rethrow_exception(failure);  // runView reports it
  if (!options.savePath.empty()) {
    writeImage(finalImage ? *finalImage : window.frame().image(), options.savePath,
               description.render.exposure);
    out << "written    " << options.savePath << "\n";
  }
  printSummary(renderer.stats(), out);
  return 0;
}

}  // namespace prism

#include "gui/Viewer.h"

#include <QApplication>
#include <QFileInfo>
#include <QKeyEvent>
#include <QTimer>
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "gui/FrameView.h"
#include "gui/MainWindow.h"
#include "gui/StatsPanel.h"
#include "image/ImageIo.h"
#include "master/live/CameraOptionsText.h"
#include "util/Percentile.h"
#include "util/PhysicalMemory.h"
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

bool sameCamera(const CameraDesc& a, const CameraDesc& b) {
  return a.position == b.position && a.lookAt == b.lookAt && a.up == b.up &&
         a.fovDegrees == b.fovDegrees;
}

// --benchmark-moves: once the first full image is on screen, orbits the camera N times, one
// move every intervalMs (like a mouse drag: moves come faster than frames, and each frame
// renders the newest), then waits for the last view's first full-resolution pass. Every pass
// completed meanwhile is a frame the user saw; their times between completions are the frame
// times.
class MoveBenchmark : public QObject {
 public:
  MoveBenchmark(MainWindow& window, int moves, double intervalMs, std::ostream& out)
      : window_(window), moves_(moves), intervalMs_(intervalMs), out_(out) {
    connect(&window, &MainWindow::passComplete, this, &MoveBenchmark::onPassComplete);
    connect(&window, &MainWindow::statsShown, this, &MoveBenchmark::onStats);
    connect(&timer_, &QTimer::timeout, this, &MoveBenchmark::move);
    timer_.setTimerType(Qt::PreciseTimer);
  }

 private:
  void move() {
    window_.cameraController().orbit(2.0f, 0.0f);  // like a 5-pixel mouse drag
    requests_.push_back({window_.cameraController().camera(), SteadyClock::now()});
    window_.viewChanged();
    if (static_cast<int>(requests_.size()) == moves_) {
      timer_.stop();
      lastMove_ = SteadyClock::now();
    }
  }

  // The rays every rank traced, counted since the viewer started, as the statistics bring them
  // (every statsInterval): the first count after the first move and the last before the end
  // give the rays traced per second while moving.
  void onStats(const LiveStats& stats) {
    if (!started_ || done_) return;
    uint64_t rays = 0;
    for (const RankStats& r : stats.ranks) rays += r.rays.total();
    const RayCount count{SteadyClock::now(), rays};
    if (!firstRays_) firstRays_ = count;
    lastRays_ = count;
  }

  double raysPerSecondWhileMoving() const {
    if (!firstRays_ || !lastRays_) return 0.0;
    const double seconds = std::chrono::duration<double>(lastRays_->at - firstRays_->at).count();
    return seconds > 0.0 ? static_cast<double>(lastRays_->rays - firstRays_->rays) / seconds : 0.0;
  }

  void onPassComplete(const DisplayPass& pass) {
    const auto now = SteadyClock::now();
    if (!started_) {
      if (pass.pass >= 1) {  // the first full image is on screen: start moving
        started_ = true;
        firstMove_ = now;
        move();
        timer_.start(static_cast<int>(std::max(1.0, intervalMs_)));
      }
      return;
    }
    if (done_) return;
    // Which move's camera this frame shows (the newest frame renders the newest view).
    std::optional<SteadyClock::time_point> requested;
    for (const Request& r : requests_) {
      if (sameCamera(r.camera, pass.camera)) requested = r.at;
    }
    if (!requested) return;  // the view from before the first move
    const bool moving = timer_.isActive();
    const bool lastView = sameCamera(pass.camera, requests_.back().camera);
    // Frames while moving: all until the last move, then the ones still showing moves. A move's
    // latency runs to its view's first frame: a later pass of the same view (the camera rested
    // between moves) refines what is already on screen.
    if (moving || !lastView || pass.firstOfView) {
      frames_.push_back({now, pass.scale, pass.pass});
      if (pass.firstOfView) latencies_.push_back(secondsSince(*requested));
    }
    if (moving || !lastView || pass.pass < 1) return;
    done_ = true;
    report(secondsSince(lastMove_));
    QTimer::singleShot(0, &window_, &QWidget::close);
  }

  void report(double fullAfterLastMove) {
    std::vector<double> frameTimes;
    for (size_t i = 1; i < frames_.size(); ++i) {
      frameTimes.push_back(
          std::chrono::duration<double>(frames_[i].at - frames_[i - 1].at).count());
    }
    const double span =
        frames_.size() > 1
            ? std::chrono::duration<double>(frames_.back().at - frames_.front().at).count()
            : 0.0;
    const double fps = span > 0.0 ? static_cast<double>(frames_.size() - 1) / span : 0.0;
    int full = 0;
    std::map<double, std::pair<FrameScale, int>, std::greater<>> reduced;  // finest first
    for (const Frame& f : frames_) {
      full += f.scale.full();
      if (!f.scale.full()) {
        auto& [scale, count] = reduced[f.scale.fraction()];
        scale = f.scale;
        ++count;
      }
    }
    std::string steps;  // "2/3: 60, 1/2: 14"
    for (const auto& [fraction, step] : reduced) {
      steps += (steps.empty() ? "" : ", ") + step.first.text() + ": " + std::to_string(step.second);
    }
    const DisplayFrame& image = window_.frame();
    char line[256];
    std::snprintf(line, sizeof line,
                  "realtime  %.1f frames/s at %dx%d, frame time median %.1f ms, p95 %.1f ms, %d "
                  "frames at full resolution, %.1f Mrays/s\n",
                  fps, image.width(), image.height(), 1e3 * percentile(frameTimes, 0.5),
                  1e3 * percentile(frameTimes, 0.95), full, raysPerSecondWhileMoving() / 1e6);
    out_ << "benchmark  " << moves_ << " camera moves, one every " << intervalMs_ << " ms, "
         << std::chrono::duration<double>(lastMove_ - firstMove_).count() << " s\n"
         << line << "frames     " << frames_.size() << " shown while moving: " << full
         << " at full resolution, " << frames_.size() - static_cast<size_t>(full) << " reduced"
         << (steps.empty() ? "" : " (of each side " + steps + ")") << "\n"
         << "latency    median " << 1e3 * percentile(latencies_, 0.5) << " ms, p95 "
         << 1e3 * percentile(latencies_, 0.95) << " ms (a move to the first frame showing it)\n"
         << "full res   " << 1e3 * fullAfterLastMove
         << " ms after the last move (its first full-resolution pass shown)\n";
    out_.flush();
  }

  struct Request {
    CameraDesc camera;
    SteadyClock::time_point at;
  };
  struct Frame {
    SteadyClock::time_point at;
    FrameScale scale;
    int pass = 0;
  };
  struct RayCount {
    SteadyClock::time_point at;
    uint64_t rays = 0;
  };

  MainWindow& window_;
  int moves_;
  double intervalMs_;
  std::ostream& out_;
  QTimer timer_;
  bool started_ = false;
  bool done_ = false;
  std::vector<Request> requests_;
  std::vector<Frame> frames_;
  std::vector<double> latencies_;
  SteadyClock::time_point firstMove_, lastMove_;
  std::optional<RayCount> firstRays_, lastRays_;
};

// shown: what the window showed last (its passes are counted there, not by the statistics,
// which a connection brings a little later).
void printSummary(const DisplayFrame& shown, const LiveStats& s, std::ostream& out) {
  out << "viewer     " << shown.state().fullPassesDone << " full passes of the last view, frame "
      << shown.frame() << "\n";
  const PhotonLiveStats& p = s.photons;
  if (p.method == CausticMethod::PhotonMap && p.passes > 0) {
    out << "photons    " << p.passes << " passes of " << p.photonsPerPass
        << ", the last: " << p.last.trace.stored << " stored, trace " << 1e3 * p.last.traceSeconds
        << " ms (" << p.last.photonsPerSecond() << " photons/s), kd-tree "
        << 1e3 * p.last.buildSeconds << " ms, radii " << 1e3 * p.last.radiiSeconds << " ms, send "
        << 1e3 * p.last.distributeSeconds << " ms, gather radius " << p.radius
        << (p.reused ? " (the first view's pass 1, reused)" : "") << "\n";
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

// Types keys into the window, queued: handled once the event loop runs, in order.
void typeKeys(QWidget& window, const std::string& keys) {
  for (const char c : keys) {
    const int key = std::isalpha(static_cast<unsigned char>(c))
                        ? Qt::Key_A + (std::toupper(static_cast<unsigned char>(c)) - 'A')
                        : static_cast<int>(c);
    const Qt::KeyboardModifiers shift =
        std::isupper(static_cast<unsigned char>(c)) ? Qt::ShiftModifier : Qt::NoModifier;
    QCoreApplication::postEvent(&window,
                                new QKeyEvent(QEvent::KeyPress, key, shift, QString(QChar(c))));
  }
}

// The source's run() on the calling thread (the coordinator), its news queued to the window.
// When the source ends by itself the window says why, and a script's window (it would quit by
// itself) quits; a failure quits with it in `failure`.
void runSource(LiveSource& source, MainWindow& window, bool scripted, std::string& endedBecause,
               std::exception_ptr& failure) {
  try {
    endedBecause = source.run([&window](bool) {  // a window takes at once, urgent or not
      QMetaObject::invokeMethod(&window, "takeNews", Qt::QueuedConnection);
    });
    if (!endedBecause.empty()) {
      const QString why = QString::fromStdString(endedBecause);
      QMetaObject::invokeMethod(
          &window, [&window, why] { window.sourceEnded(why); }, Qt::QueuedConnection);
      if (scripted) QMetaObject::invokeMethod(qApp, "quit", Qt::QueuedConnection);
    }
  } catch (...) {
    failure = std::current_exception();
    QMetaObject::invokeMethod(qApp, "quit", Qt::QueuedConnection);
  }
}

// --save: written once, when the viewer decides to quit (its view renders no more passes) or,
// failing that, when the window has closed.
class SaveOnQuit {
 public:
  SaveOnQuit(MainWindow& window, std::string path) : window_(window), path_(std::move(path)) {}
  void operator()() {
    if (done_ || path_.empty()) return;
    done_ = true;
    try {
      window_.saveImage(QString::fromStdString(path_));
    } catch (const std::exception& e) {
      error_ = e.what();
    }
  }
  bool done() const { return done_; }
  const std::string& error() const { return error_; }

 private:
  MainWindow& window_;
  std::string path_;
  bool done_ = false;
  std::string error_;
};

// Why the window should not open ("" : it may): no display, or a --save it could not write.
std::string whyNotToOpen(const ViewerOptions& options) {
  if (!haveDisplay()) {
    return "no display: set DISPLAY (or run under xvfb-run), or set QT_QPA_PLATFORM=offscreen "
           "to render without a window";
  }
  std::string why;
  if (!options.savePath.empty() && !isWritableImagePath(options.savePath, &why)) return why;
  return "";
}

}  // namespace

int runViewer(LiveSource& source, const ViewerOptions& options, std::ostream& out,
              std::ostream& err) {
  if (const std::string why = whyNotToOpen(options); !why.empty()) {
    err << "prism: error: " << why << "\n";
    return 1;
  }
  static int argc = 1;
  static char name[] = "prism";
  static char* argv[] = {name, nullptr};
  QApplication app(argc, argv);

  MainWindow window(source);
  if (options.exitAfterPasses > 0) window.limitPasses(options.exitAfterPasses);
  if (options.frameTimeMilliseconds >= 0.0) {
    window.setFrameTime(options.frameTimeMilliseconds / 1e3);
  }
  if (!options.speedupCsv.empty()) {
    const QString error = window.loadSpeedupCsv(QString::fromStdString(options.speedupCsv));
    if (!error.isEmpty()) {
      err << "prism: error: " << error.toStdString() << "\n";
      return 1;
    }
  }
  SaveOnQuit save(window, options.savePath);
  if (options.exitAfterPasses > 0) {
    QObject::connect(&window, &MainWindow::fullPassDone, &window, [&](int passes) {
      if (save.done() || passes < options.exitAfterPasses) return;
      save();
      QMetaObject::invokeMethod(&window, &QWidget::close, Qt::QueuedConnection);  // in the loop
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
  typeKeys(window, options.keys);
  std::unique_ptr<MoveBenchmark> benchmark;
  if (options.benchmarkMoves > 0) {
    benchmark = std::make_unique<MoveBenchmark>(window, options.benchmarkMoves,
                                                options.benchmarkMoveMilliseconds, out);
  }
  // A script's window (it quits by itself) leaves when the source ends; a person's stays, and
  // says why.
  const bool scripted =
      options.exitAfterPasses > 0 || options.benchmarkMoves > 0 || !options.screenshotPath.empty();
  std::string endedBecause;

  std::exception_ptr failure;
  std::thread coordinator([&] { runSource(source, window, scripted, endedBecause, failure); });
  window.fitToScreen(QSize(1600, 900));
  window.show();
  window.startRendering();
  app.exec();
  save();  // --save without --exit-after-passes: what was on show when the window closed
  source.stop();
  coordinator.join();
  if (failure) std::rethrow_exception(failure);  // the command reports it
  if (!save.error().empty()) {
    err << "prism: error: " << save.error() << "\n";
    return 1;
  }
  if (save.done()) {
    out << "written    " << options.savePath << "\n"
        << "view       " << cameraOptionsText(window.viewSettings().camera)
        << " (prism render options for this view)\n";
  }
  printSummary(window.frame(), source.stats(), out);
  if (!endedBecause.empty()) {
    err << "prism: error: " << endedBecause << "\n";
    return 1;
  }
  return 0;
}

}  // namespace prism

#include "master/commands/ViewCommand.h"

#include <cstdio>
#include <filesystem>
#include <ostream>

#include "image/ImageIo.h"
#include "master/commands/MasterSession.h"
#include "master/commands/PartialFrame.h"
#include "master/live/LocalLiveSource.h"
#include "master/remote/ViewServer.h"
#include "util/InterruptSignal.h"
#include "util/PhysicalMemory.h"

namespace prism {
namespace {

LiveOptions liveOptions(const ViewOptions& options) {
  LiveOptions live;
  live.distribution = options.render.distribution;
  live.previewScale = options.previewScale;
  live.maxPasses = options.maxPasses;
  live.frameTimeSeconds = options.frameTimeMilliseconds / 1000.0;
  live.pipeline = options.pipeline;
  live.memoryLimit = memoryLimitOrPhysical(options.render.memoryLimit);
  return live;
}

// The headless job: the live session served until it ends (interrupt, or the viewer leaving
// under --exit-with-client). No Qt is loaded on any rank.
int serve(LocalLiveSource& source, const ViewOptions& options, std::ostream& out) {
  installInterruptHandlers();  // Ctrl-C and scancel end the job cleanly, the viewer told
  ViewServer server(source, options.serve, out);
  if (options.serve.connectionFile.empty()) {
    // The token is nowhere else: without a file, the user needs it printed (to a terminal or a
    // job's output file, both the user's own).
    out << "token      " << server.token() << " (prism connect " << server.endpoint().text()
        << " with PRISM_TOKEN or --token-file)\n";
  }
  server.run();
  const LiveStats stats = source.stats();
  const FrameTimeStats& frames = stats.frameTimes;
  char line[160];
  std::snprintf(line, sizeof line,
                "rendered   %.1f frames/s over its last %d frames (median %.1f ms, p95 %.1f ms), "
                "%d full passes of the last view\n",
                frames.framesPerSecond, frames.frames, 1e3 * frames.medianSeconds,
                1e3 * frames.p95Seconds, stats.passesDone);
  out << line;
  return interruptRequested() ? kInterruptedExitCode : 0;
}

}  // namespace

int runView(const ViewOptions& options, std::ostream& out, std::ostream& err, Transport* session,
            const ViewerRunner& viewer) {
  MasterSession run(session, options.render, err);
  const bool serving = options.serve.serving();
  const auto checkArguments = [&] {
    if (serving) {
      if (!options.window.savePath.empty() || !options.window.screenshotPath.empty() ||
          options.window.benchmarkMoves > 0 || !options.window.keys.empty() ||
          options.window.exitAfterPasses > 0 || !options.window.speedupCsv.empty()) {
        throw std::runtime_error(
            "--serve shows no window here: the window's options (--save, --screenshot, --keys, "
            "--benchmark-moves, --exit-after-passes, --speedup-csv) go to `prism connect`");
      }
      parseEndpoint(options.serve.address);  // a bad address is refused before the scene loads
      return;
    }
    if (!viewer) {
      throw std::runtime_error(
          "this prism was built without the viewer (Qt5 Widgets and Charts were not found); "
          "install qtbase5-dev and libqt5charts5-dev and rebuild, or serve with --serve and "
          "connect from a machine that has it");
    }
    if (!options.window.savePath.empty()) {
      std::string why;
      if (!isWritableImagePath(options.window.savePath, &why)) throw std::runtime_error(why);
      checkMayWriteFrame(options.window.savePath, options.render.overwrite);
    }
  };
  if (!run.load(checkArguments)) return 1;  // --caustics, --photons too
  return run.runToEnd(
      [&] {
        run.start(true);  // the window shows the scene's sky
        const std::string sceneName =
            std::filesystem::path(options.render.scenePath).filename().string();
        LocalLiveSource source(run.dispatcher(), liveOptions(options), run.description(),
                               sceneName);
        if (serving) return serve(source, options, out);
        return viewer(source, options.window, out, err);
      },
      out);
}

}  // namespace prism

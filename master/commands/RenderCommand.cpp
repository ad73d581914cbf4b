#include "master/commands/RenderCommand.h"

#include <filesystem>
#include <fstream>
#include <ostream>

#include "caustics/CausticMapImages.h"
#include "caustics/PhotonImage.h"
#include "image/ImageIo.h"
#include "master/commands/MasterSession.h"
#include "master/commands/PartialFrame.h"
#include "master/commands/ProgressBar.h"
#include "master/commands/RunSummary.h"
#include "master/frame/CausticPasses.h"
#include "util/InterruptSignal.h"
#include "util/Stopwatch.h"

namespace prism {
namespace {

// Ctrl-C (or mpiexec's SIGTERM): writes the finished tiles first when asked, because under
// mpiexec a SIGKILL follows a second later; then says what happened. Returns exit status 130.
int finishInterruptedRender(const CausticFrame& result, const RenderOptions& options,
                            const std::string& output, float exposure, std::ostream& err) {
  const FrameResult& frame = result.frames;
  const size_t done = frame.tilesDone();
  std::string outcome = "nothing written (--save-partial keeps the finished tiles)";
  if (options.savePartial && done > 0) {
    const std::string partial = partialOutputPath(output);
    ImageRgb image = result.image;
    markUnfinishedTiles(image, frame.tiles, frame.tileDone);
    writeImage(image, partial, exposure, partialFrameMetadata(done, frame.tiles.size()));
    outcome = "wrote " + partial + " (partial; unfinished tiles striped magenta)";
  } else if (options.savePartial) {
    outcome = "nothing finished, nothing written";
  }
  err << "prism: interrupted by " << interruptSignalName() << ": " << done << " of "
      << frame.tiles.size() << " tiles finished";
  if (result.caustics.progressive && done == frame.tiles.size()) {
    err << " (caustics: the mean of the progressive passes finished)";
  }
  err << "; " << outcome << "\n";
  return kInterruptedExitCode;
}

// The debug images the options ask for beside the frame: where the photons landed, and the
// caustic maps in light space.
void writeDebugImages(const CausticFrame& result, const RenderOptions& options,
                      const MasterSession& session, std::ostream& err) {
  if (!options.photonImagePath.empty()) {
    if (result.lastMap) {
      const RenderSettings& r = session.description().render;
      writeImage(photonImage(*result.lastMap, session.scene().camera(), r.width, r.height),
                 options.photonImagePath, 1.0f);
    } else {
      err << "prism: warning: no photons were traced, so " << options.photonImagePath
          << " was not written\n";
    }
  }
  if (options.causticMapDebugPrefix.empty()) return;
  if (!result.causticMaps || result.causticMaps->empty()) {
    err << "prism: warning: no caustic map was built, so no --caustic-map-debug images\n";
    return;
  }
  const auto& maps = result.causticMaps->maps();
  for (size_t i = 0; i < maps.size(); ++i) {
    for (const NamedImage& image : causticMapImages(*maps[i])) {
      writeImage(
          image.image,
          options.causticMapDebugPrefix + "-light" + std::to_string(i) + "-" + image.name + ".png",
          1.0f);
    }
  }
}

// The command's own checks, before the scene is read: where the images go.
void checkOutputs(const RenderOptions& options, const std::string& output) {
  std::string why;
  if (!isWritableImagePath(output, &why)) throw std::runtime_error(why);
  checkMayWriteFrame(output, options.overwrite);
  if (!options.photonImagePath.empty() && !isWritableImagePath(options.photonImagePath, &why)) {
    throw std::runtime_error("--photon-image: " + why);
  }
}

// Renders the session's scene and writes what the options ask for; returns the exit code.
int renderAndWrite(MasterSession& session, const std::string& output, SteadyClock::time_point start,
                   std::ostream& out, std::ostream& err) {
  const RenderOptions& options = session.options();
  const CausticSettings& caustics = session.description().caustics;
  if (caustics.timeBudgetSeconds > 0.0 && caustics.method == CausticMethod::CausticMap &&
      !options.quiet) {
    err << "prism: warning: a time budget bounds progressive photon passes, and caustic mapping "
           "renders one frame: the budget is not used\n";
  }
  session.start(false, MasterSession::GeometrySending::WhileRank0Renders);
  FrameOptions frameOptions;
  frameOptions.distribution = options.distribution;
  frameOptions.stopRequested = interruptRequested;
  frameOptions.runStart = start;  // a time budget bounds the whole run
  StageProgress bar(!options.quiet);
  const auto onProgress = [&](const std::string& stage, size_t done, size_t total) {
    if (!options.statusFile.empty()) {
      std::ofstream(options.statusFile) << stage << ' ' << done << ' ' << total << '\n';
    }
    bar(stage, done, total);
  };
  const CausticFrame result = renderWithCaustics(session.dispatcher(), frameOptions, onProgress);
  bar.finish();
  const float exposure = session.description().render.exposure;
  if (result.frames.interrupted) {
    return finishInterruptedRender(result, options, output, exposure, err);
  }
  if (result.caustics.noCasters && !options.quiet) {
    err << "prism: warning: caustics asked for, but no light reaches a caustic caster "
           "(a reflective or transparent object): rendered without photons\n";
  }
  const auto writeStart = SteadyClock::now();
  writeImage(result.image, output, exposure);
  const double writeSeconds = secondsSince(writeStart);
  writeDebugImages(result, options, session, err);
  if (!options.quiet) {
    RunSummary summary;
    const SessionSetUp& setUp = session.setUp();
    summary.parseSeconds = setUp.parseSeconds;
    summary.broadcastSeconds = setUp.broadcastSeconds;
    summary.broadcastBytes = setUp.broadcastBytes;
    summary.geometryShare = setUp.geometryShare.describe();
    summary.buildSeconds = setUp.buildSeconds;
    summary.instructionSet = setUp.instructionSet.describe();
    summary.writeSeconds = writeSeconds;
    summary.scenePath = options.scenePath;
    summary.outputPath = output;
    summary.settings = session.description().render;
    summary.sceneStats = session.scene().buildStats();
    summary.lightCount = session.description().lights.size();
    summary.sceneNotes = session.description().notes;
    summary.schedule = options.distribution.schedule;
    summary.frame = &result.frames;
    summary.caustics = &result.caustics;
    summary.totalSeconds = secondsSince(start);
    if (result.frames.firstTileAt) {
      summary.firstTileSeconds =
          std::chrono::duration<double>(*result.frames.firstTileAt - start).count();
    }
    printRunSummary(summary, out);
  }
  return 0;
}

}  // namespace

std::string defaultOutputPath(const std::string& scenePath) {
  return std::filesystem::path(scenePath).stem().string() + ".png";
}

int runRender(const RenderOptions& options, std::ostream& out, std::ostream& err,
              Transport* session) {
  // From here on Ctrl-C stops the run (at the first tile boundary) instead of the process.
  installInterruptHandlers();
  const auto start = SteadyClock::now();
  const std::string output =
      options.outputPath.empty() ? defaultOutputPath(options.scenePath) : options.outputPath;
  MasterSession run(session, options, err);
  if (!run.load([&] { checkOutputs(options, output); })) return 1;
  return run.runToEnd([&] { return renderAndWrite(run, output, start, out, err); }, out);
}

}  // namespace prism

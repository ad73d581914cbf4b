#include "master/commands/RenderCommand.h"

#include <filesystem>
#include <fstream>
#include <memory>
#include <ostream>
#include <utility>

#include "caustics/CausticMapImages.h"
#include "caustics/CausticMapMemory.h"
#include "caustics/PhotonImage.h"
#include "image/ImageIo.h"
#include "master/commands/PartialFrame.h"
#include "master/commands/ProgressBar.h"
#include "master/commands/RunSummary.h"
#include "master/runtime/CausticPasses.h"
#include "master/runtime/FrameRenderer.h"
#include "master/runtime/ResourceCheck.h"
#include "master/runtime/SlaveShutdown.h"
#include "parse/SceneLoader.h"
#include "scene/Scene.h"
#include "scene/SceneValidation.h"
#include "transport/Transport.h"
#include "util/InterruptSignal.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {
void applyOverrides(const RenderOptions& o, RenderSettings& s) {
  if (o.width) s.width = *o.width;
  if (o.height) s.height = *o.height;
  if (o.samples) s.samplesPerPixel = *o.samples;
  if (o.maxDepth) s.maxDepth = *o.maxDepth;
  if (o.seed) s.seed = *o.seed;
  if (o.exposure) s.exposure = *o.exposure;
  if (o.triangleTest) s.triangleTest = *o.triangleTest;
}

void applyOverrides(const RenderOptions& o, CausticSettings& c) {
  if (o.causticMethod) c.method = *o.causticMethod;
  if (o.photons) c.photons = *o.photons;
  if (o.gather) {
    c.gather = *o.gather;
    c.automaticGather = false;
  }
  if (o.gatherNoise) {
    c.gatherNoise = *o.gatherNoise;
    c.automaticGather = true;
  }
  if (o.passes) c.passes = *o.passes;
  if (o.progressive) c.progressive = *o.progressive;
  if (o.gatherRadius) c.maxRadius = c.radius = *o.gatherRadius;
  if (o.timeBudget) c.timeBudgetSeconds = *o.timeBudget;
  if (o.mapResolution) c.mapResolution = *o.mapResolution;
  if (o.mapSteps) c.mapSteps = *o.mapSteps;
  if (o.mapBlurSigma) c.mapBlurSigma = *o.mapBlurSigma;
  if (o.mapBlurRadius) c.mapBlurRadius = *o.mapBlurRadius;
  if (o.mapPaths) c.mapPaths = *o.mapPaths;
  // Caustic-map parameters alone ask for caustic mapping.
  if ((o.mapResolution || o.mapSteps || o.mapBlurSigma || o.mapBlurRadius || o.mapPaths) &&
      !o.causticMethod && c.method == CausticMethod::None) {
    c.method = CausticMethod::CausticMap;
  }
  // Asking for passes, a budget or a photon image means asking for photon mapping.
  if ((o.progressive || o.passes || o.timeBudget || o.photons) && !o.causticMethod &&
      c.method == CausticMethod::None) {
    c.method = CausticMethod::PhotonMap;
  }
}

SceneDescription loadSceneWithOverrides(const RenderOptions& options) {
  const MemoryLimit limit = memoryLimitOrPhysical(options.memoryLimit);
  SceneDescription description = loadScene(options.scenePath, limit);
  applyOverrides(options, description.render);
  applyOverrides(options, description.caustics);
  validate(description);
  checkRenderFits(description.render, limit);
  checkTilesFit(description.render, options.distribution.tileSize, limit);
  checkCausticsFit(description.caustics, description.lights.size(), limit);
  checkSceneFits(description, options.distribution.tileSize, limit);
  return description;
}

int failBeforeScene(Transport* session, const std::string& what, std::ostream& err) {
  if (session) {
    std::vector<uint8_t> bytes = wire::encode(wire::ErrorMessage{what});
    session->broadcast(bytes, kSceneBroadcastTimeoutSeconds);
  }
  err << "prism: error: " << what << "\n";
  return 1;
}

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
  RunSummary summary;
  SceneDescription description;
  try {
    std::string why;
    if (!isWritableImagePath(output, &why)) throw std::runtime_error(why);
    checkMayWriteFrame(output, options.overwrite);
    if (!options.photonImagePath.empty() && !isWritableImagePath(options.photonImagePath, &why)) {
      throw std::runtime_error("--photon-image: " + why);
    }
    const auto parseStart = SteadyClock::now();
    description = loadSceneWithOverrides(options);
    summary.parseSeconds = secondsSince(parseStart);
  } catch (const std::exception& e) {
    return failBeforeScene(session, e.what(), err);
  }

  int exitCode = 0;
  std::vector<bool> silentRanks;
  try {
    if (session) {
      const auto broadcastStart = SteadyClock::now();
      std::vector<uint8_t> bytes = wire::encodeScene(description);
      session->broadcast(bytes, kSceneBroadcastTimeoutSeconds);
      summary.broadcastSeconds = secondsSince(broadcastStart);
      summary.broadcastBytes = bytes.size();
    }
    const auto buildStart = SteadyClock::now();
    // The description's cube-map faces move into the scene: nothing below reads them.
    const Scene scene(description, std::exchange(description.environment, std::nullopt));
    summary.buildSeconds = secondsSince(buildStart);
    checkCausticMapsFit(scene, memoryLimitOrPhysical(options.memoryLimit));

    FrameOptions frameOptions;
    frameOptions.distribution = options.distribution;
    frameOptions.stopRequested = interruptRequested;
    std::unique_ptr<ProgressBar> progress;
    std::string stage;
    const auto onProgress = [&](const std::string& label, size_t done, size_t total) {
      if (!options.statusFile.empty()) {
        std::ofstream(options.statusFile) << label << ' ' << done << ' ' << total << '\n';
      }
      if (options.quiet) return;
      if (!progress || label != stage) {
        if (progress) progress->finish();
        progress = std::make_unique<ProgressBar>(label, total, "tiles", true);
        stage = label;
      }
      progress->setTotal(total);
      progress->update(done);
    };
    SlaveLink link(session, options.distribution);
    const CausticFrame result = renderWithCaustics(scene, frameOptions, link, onProgress);
    if (progress) progress->finish();
    const FrameResult& frame = result.frames;
    silentRanks = link.retiredRanks();
    if (frame.interrupted) {
      exitCode = finishInterruptedRender(result, options, output, description.render.exposure, err);
      out.flush();
      err.flush();
      if (session && interruptSignalName() == std::string("SIGTERM")) {
        leaveEndingJob(*session, exitCode);
      }
      return shutDownSlaves(session, exitCode, silentRanks, err);
    }
    if (result.caustics.noCasters && !options.quiet) {
      err << "prism: warning: caustics asked for, but no light reaches a caustic caster "
             "(a reflective or transparent object): rendered without photons\n";
    }

    const auto writeStart = SteadyClock::now();
    writeImage(result.image, output, description.render.exposure);
    summary.writeSeconds = secondsSince(writeStart);
    if (!options.photonImagePath.empty()) {
      if (result.lastMap) {
        const RenderSettings& r = description.render;
        writeImage(photonImage(*result.lastMap, scene.camera(), r.width, r.height),
                   options.photonImagePath, 1.0f);
      } else {
        err << "prism: warning: no photons were traced, so " << options.photonImagePath
            << " was not written\n";
      }
    }

    if (!options.causticMapDebugPrefix.empty()) {
      if (result.causticMaps && !result.causticMaps->empty()) {
        const auto& maps = result.causticMaps->maps();
        for (size_t i = 0; i < maps.size(); ++i) {
          for (const NamedImage& image : causticMapImages(*maps[i])) {
            writeImage(image.image,
                       options.causticMapDebugPrefix + "-light" + std::to_string(i) + "-" +
                           image.name + ".png",
                       1.0f);
          }
        }
      } else {
        err << "prism: warning: no caustic map was built, so no --caustic-map-debug images\n";
      }
    }

    if (!options.quiet) {
      summary.scenePath = options.scenePath;
      summary.outputPath = output;
      summary.settings = description.render;
      summary.sceneStats = scene.buildStats();
      summary.lightCount = description.lights.size();
      summary.schedule = options.distribution.schedule;
      summary.frame = &frame;
      summary.caustics = &result.caustics;
      summary.totalSeconds = secondsSince(start);
      printRunSummary(summary, out);
    }
  } catch (const std::exception& e) {
    err << "prism: error: " << e.what() << "\n";
    exitCode = 1;
  }
  out.flush();
  return shutDownSlaves(session, exitCode, silentRanks, err);
}

}  // namespace prism

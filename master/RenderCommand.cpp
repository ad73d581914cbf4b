#include "master/RenderCommand.h"

#include <chrono>
#include <filesystem>
#include <ostream>

#include "image/ImageIo.h"
#include "master/FrameRenderer.h"
#include "master/ProgressBar.h"
#include "master/ResourceCheck.h"
#include "master/RunSummary.h"
#include "master/SlaveShutdown.h"
#include "parse/SceneLoader.h"
#include "scene/Scene.h"
#include "slave/SlaveLoop.h"
#include "transport/MpiSession.h"
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

std::string defaultOutputPath(const std::string& scenePath) {
  return std::filesystem::path(scenePath).stem().string() + ".png";
}

int runRender(const RenderOptions& options, std::ostream& out, std::ostream& err,
              MpiSession* session) {
  if (session && session->rank() != 0) {
    SlaveOptions slave;
    slave.threads = options.threads;
    slave.fault = options.fault;
    return runSlave(*session, slave);
  }
  constexpr double kBroadcastTimeoutSeconds = 600.0;
  const auto start = std::chrono::steady_clock::now();
  const std::string output =
      options.outputPath.empty() ? defaultOutputPath(options.scenePath) : options.outputPath;
  RunSummary summary;
  SceneDescription description;
  try {
    std::string why;
    if (!isWritableImagePath(output, &why)) throw std::runtime_error(why);
    const auto parseStart = std::chrono::steady_clock::now();
    description = loadScene(options.scenePath);
    summary.parseSeconds = secondsSince(parseStart);
    applyOverrides(options, description.render);
    checkRenderFits(description.render, physicalMemoryBytes());
  } catch (const std::exception& e) {
    // The slaves wait for a scene: send them the error instead so they stop at once.
    if (session) {
      std::vector<uint8_t> bytes = wire::encodeError({e.what()});
      session->broadcast(bytes, kBroadcastTimeoutSeconds);
    }
    err << "prism: error: " << e.what() << "\n";
    return 1;
  }

  int exitCode = 0;
  std::vector<bool> silentRanks;
  try {
    if (session) {
      const auto broadcastStart = std::chrono::steady_clock::now();
      std::vector<uint8_t> bytes = wire::encodeScene(description);
      session->broadcast(bytes, kBroadcastTimeoutSeconds);
      summary.broadcastSeconds = secondsSince(broadcastStart);
      summary.broadcastBytes = bytes.size();
    }
    const auto buildStart = std::chrono::steady_clock::now();
    const Scene scene(description);
    summary.buildSeconds = secondsSince(buildStart);

    FrameOptions frameOptions;
    frameOptions.threads = options.threads;
    frameOptions.tileSize = options.tileSize;
    frameOptions.schedule = options.schedule;
    frameOptions.leaseSeconds = options.leaseSeconds;
    frameOptions.prefetch = options.prefetch;
    ProgressBar progress("render", 0, "tiles", !options.quiet);
    frameOptions.progress = [&](size_t done, size_t total) {
      progress.setTotal(total);
      progress.update(done);
    };
    const FrameResult frame = renderFrame(scene, frameOptions, session);
    progress.finish();
    for (const WorkerStats& w : frame.workers) silentRanks.push_back(w.retired);

    const auto writeStart = std::chrono::steady_clock::now();
    writeImage(frame.image, output, description.render.exposure);
    summary.writeSeconds = secondsSince(writeStart);

    if (!options.quiet) {
      summary.scenePath = options.scenePath;
      summary.outputPath = output;
      summary.settings = description.render;
      summary.sceneStats = scene.buildStats();
      summary.lightCount = description.lights.size();
      summary.schedule = options.schedule;
      summary.frame = &frame;
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

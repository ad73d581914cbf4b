#include "master/RenderCommand.h"

#include <chrono>
#include <filesystem>
#include <ostream>

#include "image/ImageIo.h"
#include "master/FrameRenderer.h"
#include "master/ProgressBar.h"
#include "master/ResourceCheck.h"
#include "master/RunSummary.h"
#include "parse/SceneLoader.h"
#include "scene/Scene.h"

namespace prism {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

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

int runRender(const RenderOptions& options, std::ostream& out, std::ostream& err) {
  const auto start = std::chrono::steady_clock::now();
  const std::string output =
      options.outputPath.empty() ? defaultOutputPath(options.scenePath) : options.outputPath;
  try {
    std::string why;
    if (!isWritableImagePath(output, &why)) throw std::runtime_error(why);

    const auto parseStart = std::chrono::steady_clock::now();
    SceneDescription description = loadScene(options.scenePath);
    const double parseSeconds = secondsSince(parseStart);
    applyOverrides(options, description.render);
    checkRenderFits(description.render, physicalMemoryBytes());

    const auto buildStart = std::chrono::steady_clock::now();
    const Scene scene(description);
    const double buildSeconds = secondsSince(buildStart);

    FrameOptions frameOptions;
    frameOptions.threads = options.threads;
    frameOptions.tileSize = options.tileSize;
    ProgressBar progress("render", 0, "tiles", !options.quiet);
    frameOptions.progress = [&](size_t done, size_t total) {
      progress.setTotal(total);
      progress.update(done);
    };
    const FrameResult frame = renderFrame(scene, frameOptions);
    progress.finish();

    const auto writeStart = std::chrono::steady_clock::now();
    writeImage(frame.image, output, description.render.exposure);
    const double writeSeconds = secondsSince(writeStart);

    if (!options.quiet) {
      RunSummary summary;
      summary.scenePath = options.scenePath;
      summary.outputPath = output;
      summary.settings = description.render;
      summary.sceneStats = scene.buildStats();
      summary.lightCount = description.lights.size();
      summary.frame = &frame;
      summary.parseSeconds = parseSeconds;
      summary.buildSeconds = buildSeconds;
      summary.writeSeconds = writeSeconds;
      summary.totalSeconds = secondsSince(start);
      printRunSummary(summary, out);
    }
    return 0;
  } catch (const std::exception& e) {
    err << "prism: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace prism

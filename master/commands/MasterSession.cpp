#include "master/commands/MasterSession.h"

#include <ostream>
#include <stdexcept>
#include <utility>

#include "master/frame/ResourceCheck.h"
#include "parse/SceneLoader.h"
#include "scene/SceneValidation.h"
#include "util/PhysicalMemory.h"
#include "util/Stopwatch.h"

namespace prism {
namespace {

DispatchSettings dispatchSettingsOf(const RenderOptions& options) {
  DispatchSettings settings;
  settings.instructionSet = options.instructionSet;
  settings.geometryShare = options.geometryShare;
  settings.distribution = options.distribution;
  settings.memoryLimit = options.memoryLimit;
  return settings;
}

}  // namespace

SceneDescription loadSceneWithOverrides(const RenderOptions& options) {
  const MemoryLimit limit = memoryLimitOrPhysical(options.memoryLimit);
  SceneDescription description = loadScene(options.scenePath, limit);
  applyOverrides(options, description.render);
  applyOverrides(options, description.caustics);
  applyOverrides(options, description.camera);
  validate(description);
  checkRenderFits(description.render, limit);
  checkTilesFit(description.render, options.distribution.tileSize, limit);
  checkCausticsFit(description.caustics, description.lights.size(), limit);
  checkSceneFits(description, options.distribution.tileSize, limit);
  return description;
}

MasterSession::MasterSession(Transport* transport, RenderOptions options, std::ostream& err)
    : options_(std::move(options)),
      err_(err),
      dispatch_(transport, dispatchSettingsOf(options_), err) {}

bool MasterSession::load(const std::function<void()>& check) {
  try {
    if (check) check();
    const auto start = SteadyClock::now();
    description_ = loadSceneWithOverrides(options_);
    dispatch_.setUp().parseSeconds = secondsSince(start);
    // What the files held that Prism does not model, said before the render starts.
    for (const std::string& warning : description_.warnings) {
      err_ << "prism: warning: " << warning << "\n";
    }
    // After the parse, which the slaves' start-up overlaps: their Hellos are waiting by now.
    description_.render.instructionSet = dispatch_.chooseInstructionSet();
    return true;
  } catch (const std::exception& e) {
    refuse(e.what());
    return false;
  }
}

int MasterSession::runToEnd(const std::function<int()>& work, std::ostream& out) {
  int exitCode = 0;
  try {
    exitCode = work();
  } catch (const std::exception& e) {
    err_ << "prism: error: " << e.what() << "\n";
    exitCode = 1;
  }
  out.flush();
  return finish(exitCode);
}

}  // namespace prism

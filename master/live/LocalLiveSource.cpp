#include "master/live/LocalLiveSource.h"

namespace prism {

ViewSettings initialView(const SceneDescription& description) {
  ViewSettings view;
  view.camera = description.camera;
  view.samplesPerPixel = description.render.samplesPerPixel;
  view.caustics = description.caustics.method;
  view.photonsPerPass = description.caustics.photons;
  return view;
}

ViewerStart LocalLiveSource::startOf(const SceneDescription& description,
                                     const std::string& sceneName, const LiveRenderer& renderer) {
  ViewerStart start;
  start.sceneName = sceneName;
  start.width = description.render.width;
  start.height = description.render.height;
  start.exposure = description.render.exposure;
  start.home = description.camera;
  start.view = initialView(description);
  start.causticMapsRefusal = renderer.causticMapsRefusal().value_or("");
  // Rank 0 chose it for the job (master/dispatch/JobInstructionSet.h) before the scene went out;
  // its scene runs it (Auto resolved).
  start.instructionSet = instructionSetName(renderer.scene().instructionSet());
  return start;
}

LocalLiveSource::LocalLiveSource(WorkDispatcher& dispatcher, const LiveOptions& options,
                                 const SceneDescription& description, const std::string& sceneName)
    : renderer_(std::make_unique<LiveRenderer>(dispatcher, options)),
      feed_(description.render.width, description.render.height, description.render.exposure),
      start_(startOf(description, sceneName, *renderer_)) {}

LocalLiveSource::LocalLiveSource(const Scene& scene, const LiveOptions& options,
                                 const SceneDescription& description, const std::string& sceneName,
                                 Transport* cluster)
    : renderer_(std::make_unique<LiveRenderer>(scene, options, cluster)),
      feed_(description.render.width, description.render.height, description.render.exposure),
      start_(startOf(description, sceneName, *renderer_)) {}

std::string LocalLiveSource::run(NewsWake wake) {
  feed_.setWake(std::move(wake));
  renderer_->run(feed_);
  return "";
}

}  // namespace prism

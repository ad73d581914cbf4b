// A LiveSource in this process: LiveRenderer on the run's dispatcher, its news through a
// LiveFeed. What `prism view` shows in its window and what `prism view --serve` serves.
#pragma once

#include <memory>

#include "master/live/LiveFeed.h"
#include "master/live/LiveRenderer.h"
#include "master/live/LiveSource.h"

namespace prism {

class LocalLiveSource final : public LiveSource {
 public:
  // On the run's dispatcher, whose scene it renders (sceneName: the file's name).
  LocalLiveSource(WorkDispatcher& dispatcher, const LiveOptions& options,
                  const SceneDescription& description, const std::string& sceneName);
  // On a dispatcher of its own (tests; cluster null: this process alone).
  LocalLiveSource(const Scene& scene, const LiveOptions& options,
                  const SceneDescription& description, const std::string& sceneName,
                  Transport* cluster = nullptr);

  const ViewerStart& start() const override { return start_; }
  void setView(const ViewSettings& view) override { renderer_->setView(view); }
  std::string run(NewsWake wake) override;
  void stop() override { renderer_->stop(); }
  DisplayNews take(bool whole = false) override { return feed_.take(whole); }
  ImageRgb fullImage() override { return feed_.image(); }
  LiveStats stats() override { return renderer_->stats(); }
  std::shared_ptr<const CausticMapEstimator> causticMaps(bool blur) override {
    return renderer_->causticMaps(blur);
  }

  LiveRenderer& renderer() { return *renderer_; }

 private:
  static ViewerStart startOf(const SceneDescription& description, const std::string& sceneName,
                             const LiveRenderer& renderer);

  std::unique_ptr<LiveRenderer> renderer_;
  LiveFeed feed_;
  ViewerStart start_;
};

// The view a scene opens with: its camera, samples per pixel and caustics.
ViewSettings initialView(const SceneDescription& description);

}  // namespace prism

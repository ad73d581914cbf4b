// A LiveSource whose news the test writes (a test double): the window under test takes what the
// test posted, and every view it asks for is recorded.
#pragma once

#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "master/live/LiveSource.h"
#include "master/live/LocalLiveSource.h"
#include "master/live/NewsBoard.h"

namespace prism {

class ScriptedSource final : public LiveSource {
 public:
  explicit ScriptedSource(const SceneDescription& d, const std::string& lightSpaceRefusal = "")
      : board_(d.render.width, d.render.height) {
    start_.lightSpaceRefusal = lightSpaceRefusal;
    start_.sceneName = "test";
    start_.width = d.render.width;
    start_.height = d.render.height;
    start_.exposure = d.render.exposure;
    start_.home = d.camera;
    start_.view = initialView(d);
  }

  void post(DisplayNews news) { board_.post(std::move(news)); }

  const ViewerStart& start() const override { return start_; }
  void setView(const ViewSettings& view) override { requested.push_back(view); }
  std::string run(NewsWake) override { return ""; }
  void stop() override {}
  DisplayNews take(bool whole) override { return board_.take(whole); }
  ImageRgb fullImage() override { throw std::runtime_error("no full image in this test"); }
  LiveStats stats() override { return {}; }
  std::shared_ptr<const CausticMapEstimator> causticMaps(bool) override {
    throw std::runtime_error("no caustic maps in this test");
  }

  std::vector<ViewSettings> requested;

 private:
  ViewerStart start_;
  NewsBoard board_;
};

}  // namespace prism

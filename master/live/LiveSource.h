// What a viewer drives: a live renderer in this process (LocalLiveSource) or one in a job
// elsewhere, over a connection (master/remote/ViewClient.h). The window (gui/) and the view
// server (master/remote/ViewServer.h) both use a source through this interface only, so the
// window on a desk and the window beside the job are one code path.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "caustics/CausticMapEstimator.h"
#include "image/ImageRgb.h"
#include "master/live/DisplayNews.h"
#include "master/live/LiveRenderer.h"

namespace prism {

// What the window opens with.
struct ViewerStart {
  std::string sceneName;  // the scene file's name, for the title
  int32_t width = 0;      // the frame, in display pixels
  int32_t height = 0;
  float exposure = 1.0f;  // what the display bytes were encoded with (and a PNG save uses)
  CameraDesc home;        // the scene's camera (the reset key)
  ViewSettings view;      // the view to show first
  // The view is already rendering (a viewer that came back to a job): show what has
  // accumulated instead of asking for the view again.
  bool resume = false;
  // Why switching caustic maps on would be refused ("" : it would not).
  std::string causticMapsRefusal;
  // Why the light-space images of the caustic maps cannot be shown here ("" : they can).
  std::string lightSpaceRefusal;
  // The ray kernels' instruction set on every rank ("x86-64-v4"; util/InstructionSet.h).
  std::string instructionSet;
};

// Called when news waits to be taken. urgent: a pass began or completed (a viewer shows that at
// once); otherwise only tiles' progress or statistics changed (a viewer over a link may gather
// such news a few milliseconds before it takes).
using NewsWake = std::function<void(bool urgent)>;

class LiveSource {
 public:
  virtual ~LiveSource() = default;

  virtual const ViewerStart& start() const = 0;
  // Ends the current frame and starts rendering this view. Any thread.
  virtual void setView(const ViewSettings& view) = 0;
  // Renders (or receives) until stop(), calling wake() whenever news waits to be taken (once,
  // and once more if urgent news follows, until the next take); wake() should only wake the
  // viewer's thread. Returns "" after stop(), or why the source ended by
  // itself (the job ended, the connection was lost). Throws when rendering fails.
  virtual std::string run(NewsWake wake) = 0;
  // Makes run() return soon. Any thread.
  virtual void stop() = 0;
  // The news since the last take (LiveFeed::take); `whole`: every pixel. Any thread.
  virtual DisplayNews take(bool whole = false) = 0;
  // The image on show at full precision (an EXR save). Throws std::runtime_error when it
  // cannot be had (the connection went).
  virtual ImageRgb fullImage() = 0;
  // The latest statistics.
  virtual LiveStats stats() = 0;
  // The scene's caustic maps for the light-space images (LiveRenderer::causticMaps); throws
  // with the reason when start().lightSpaceRefusal says they cannot be had here.
  virtual std::shared_ptr<const CausticMapEstimator> causticMaps(bool blur) = 0;
};

}  // namespace prism

// The viewer's next pass, as LiveRenderer's coordinator chose it under its lock (its frame id
// already taken): shared by the files of master/live/LiveRenderer*.cpp.
#pragma once

#include "master/live/LiveRenderer.h"

namespace prism {

// The next pass to render, chosen under the lock; its frame id is taken already.
struct LiveRenderer::PassPlan {
  int index = 0;
  uint32_t frame = 0;
  uint64_t viewId = 0;
  ViewSettings view;
  FrameScale scale;
  bool firstOfView = false;
};

}  // namespace prism

// `prism view`: the run's session loads the scene and broadcasts it, and rank 0 goes to the Qt
// viewer (gui/), which renders it live through LiveRenderer on the session's dispatcher. Qt-free:
// the viewer is passed in as a function, so prism_app and its tests build and run without Qt, and a
// build without Qt says so clearly.
#pragma once

#include <iosfwd>
#include <string>

#include "master/commands/RenderCommand.h"
#include "master/live/ViewerOptions.h"
#include "master/live/ViewerRunner.h"
#include "master/remote/ServeOptions.h"
#include "scene/Scene.h"

namespace prism {

struct ViewOptions {
  RenderOptions render;  // scene path, overrides, threads and distribution, as for `render`
  int previewScale = 4;  // frames while moving may drop down to 1/previewScale of each side
  int maxPasses = 64;    // full-resolution passes before the view stops refining
  double frameTimeMilliseconds = 1000.0 / 30;  // target for frames while moving; 0: none
  bool pipeline = true;  // queue the next frame before the current one's last tiles return
  ViewerOptions window;  // what the window does besides showing
  ServeOptions serve;    // --serve: no window here; a viewer connects
};

class Transport;

// Rank 0 loads and broadcasts the scene and runs `viewer`; other ranks are slaves exactly as
// in `render`. Without a viewer (Qt was not found at build time) it fails with a clear error.
int runView(const ViewOptions& options, std::ostream& out, std::ostream& err, Transport* session,
            const ViewerRunner& viewer);

}  // namespace prism

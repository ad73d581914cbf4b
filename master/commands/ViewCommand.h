// `prism view`: the run's session loads the scene and broadcasts it, and rank 0 goes to the Qt
// viewer (gui/), which renders it live through LiveRenderer on the session's dispatcher. Qt-free:
// the viewer is passed in as a function, so prism_app and its tests build and run without Qt, and a
// build without Qt says so clearly.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>

#include "master/commands/RenderCommand.h"
#include "scene/Scene.h"

namespace prism {

struct ViewOptions {
  RenderOptions render;  // scene path, overrides, threads and distribution, as for `render`
  int previewScale = 4;  // frames while moving may drop down to 1/previewScale of each side
  int maxPasses = 64;    // full-resolution passes before the view stops refining
  double frameTimeMilliseconds = 1000.0 / 30;  // target for frames while moving; 0: none
  bool pipeline = true;    // queue the next frame before the current one's last tiles return
  std::string speedupCsv;  // loaded into the statistics panel at start
  // For scripts, tests and benchmarks (the window still opens):
  int exitAfterPasses = 0;         // quit when this many full passes of the first view are done
  std::string savePath;            // save the image here when quitting
  std::string screenshotPath;      // grab the whole window here ...
  double screenshotSeconds = 2.0;  // ... this long after start, then quit
  int benchmarkMoves = 0;          // move the camera this often, print frame rates, quit
  double benchmarkMoveMilliseconds = 10.0;  // one move per this interval (a mouse drag's rate)
  std::string keys;  // typed into the window at start, in order (letters, + - =)
};

class Transport;
class MasterSession;

// Runs the viewer on rank 0 over the run's session (its scene, and the dispatcher it renders
// with); returns the process exit code.
using ViewerRunner = std::function<int(MasterSession& session, const ViewOptions& options,
                                       std::ostream& out, std::ostream& err)>;

// Rank 0 loads and broadcasts the scene and runs `viewer`; other ranks are slaves exactly as
// in `render`. Without a viewer (Qt was not found at build time) it fails with a clear error.
int runView(const ViewOptions& options, std::ostream& out, std::ostream& err, Transport* session,
            const ViewerRunner& viewer);

}  // namespace prism

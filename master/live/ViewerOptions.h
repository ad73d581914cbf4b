// What the viewer window does besides showing: the options `prism view` and `prism connect`
// share (the window is the same whether the job is in this process or elsewhere).
#pragma once

#include <string>

namespace prism {

struct ViewerOptions {
  std::string speedupCsv;  // loaded into the statistics panel at start
  // For scripts, tests and benchmarks (the window still opens):
  // quit when this many full passes of the view asked for last are done (the view renders no
  // more than that)
  int exitAfterPasses = 0;
  std::string savePath;        // save the image here when quitting (written where the window is)
  std::string screenshotPath;  // grab the whole window here ...
  double screenshotSeconds = 2.0;           // ... this long after start, then quit
  int benchmarkMoves = 0;                   // move the camera this often, print frame rates, quit
  double benchmarkMoveMilliseconds = 10.0;  // one move per this interval (a mouse drag's rate)
  std::string keys;  // typed into the window at start, in order (letters, + - =)
  // The renderer's target for frames while moving, asked for with every view (`prism connect
  // --frame-time`); negative: the job's own.
  double frameTimeMilliseconds = -1.0;
};

}  // namespace prism

// The viewer window as a function the commands are handed (`prism view` runs it on rank 0's
// live renderer, `prism connect` on a job's over a connection), so prism_app and its tests
// build and run without Qt; gui/ provides it (gui/ViewerModule.h).
#pragma once

#include <functional>
#include <iosfwd>

#include "master/live/ViewerOptions.h"

namespace prism {

class LiveSource;

// Runs the viewer window on a live source (in this process, or a job's over a connection);
// returns the process exit code.
using ViewerRunner = std::function<int(LiveSource& source, const ViewerOptions& options,
                                       std::ostream& out, std::ostream& err)>;

}  // namespace prism

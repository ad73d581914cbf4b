// The viewer window on a live source (`prism view` on rank 0: LiveRenderer on the coordinator
// thread, the one that calls MPI; `prism connect`: a job's over a connection): the Qt
// application, the window and the source's run() on a thread of its own. Matches ViewerRunner
// (master/live/ViewerRunner.h).
#pragma once

#include <iosfwd>

#include "master/live/ViewerRunner.h"

namespace prism {

int runViewer(LiveSource& source, const ViewerOptions& options, std::ostream& out,
              std::ostream& err);

}  // namespace prism

// `prism view` on rank 0: the Qt application, the window, and LiveRenderer on its coordinator
// thread (the one thread that calls MPI). Matches ViewerRunner (master/commands/ViewCommand.h).
#pragma once

#include <iosfwd>

#include "master/commands/ViewCommand.h"

namespace prism {

int runViewer(MasterSession& session, const ViewOptions& options, std::ostream& out,
              std::ostream& err);

}  // namespace prism

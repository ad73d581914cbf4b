// `prism view` on rank 0: the Qt application, the window, and LiveRenderer on its coordinator
// thread (the one thread that calls MPI). Matches ViewerRunner (master/commands/ViewCommand.h).
#pragma once

#include <iosfwd>

#include "master/commands/ViewCommand.h"

namespace prism {

int runViewer(const Scene& scene, const SceneDescription& description, const ViewOptions& options,
              Transport* session, std::ostream& out, std::ostream& err);

}  // namespace prism

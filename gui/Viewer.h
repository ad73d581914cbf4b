// `prism view` on rank 0: the Qt application, the window, and LiveRenderer on its coordinator
// thread (the one thread that calls MPI). Matches ViewerRunner (master/ViewCommand.h).
#pragma once

#include <iosfwd>

#include "master/ViewCommand.h"

namespace prism {

int runViewer(const Scene& scene, const SceneDescription& description, const ViewOptions& options,
              Transport* session, std::ostream& out, std::ostream& err);

}  // namespace prism

// `prism render`: load a scene, apply command-line overrides, render, write the image, and
// print a summary.
#pragma once

#include <iosfwd>
#include <string>

#include "master/commands/RenderOptions.h"

namespace prism {

// The output path used when none is given: the scene's file name with a .png extension.
std::string defaultOutputPath(const std::string& scenePath);

class Transport;

// Runs the command on rank 0 (or the only process); returns the process exit code. Errors go
// to err as "prism: error: ...". In an MPI run the session's other ranks are slaves.
int runRender(const RenderOptions& options, std::ostream& out, std::ostream& err,
              Transport* session = nullptr);

}  // namespace prism

// `prism connect`: the viewer window on a job that serves its live session (`prism view
// --serve`), from a connection file or HOST:PORT with the token from --token-file or
// PRISM_TOKEN (never from the command line, where `ps` shows it to everyone).
#pragma once

#include <iosfwd>
#include <string>

#include "master/commands/ViewCommand.h"
#include "master/live/ViewerOptions.h"

namespace prism {

class Transport;

struct ConnectCommandOptions {
  std::string target;     // a connection file, or HOST:PORT
  std::string tokenFile;  // with HOST:PORT: the token's file (else $PRISM_TOKEN)
  double timeoutSeconds = 10.0;
  ViewerOptions window;
};

// session: an MPI launch's (refused: a viewer runs alone) or null.
int runConnect(const ConnectCommandOptions& options, std::ostream& out, std::ostream& err,
               Transport* session, const ViewerRunner& viewer);

}  // namespace prism

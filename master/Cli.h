// The `prism` command line: subcommands, their options and their help.
#pragma once

#include <string>
#include <vector>

#include "master/SpeedupChart.h"
#include "master/ViewCommand.h"

namespace prism {

class MpiSession;

// Parses argv and runs the chosen subcommand; returns the process exit code. In an MPI run
// every rank parses the same arguments; only rank 0 prints help and usage errors. viewer runs
// `prism view` on rank 0 and chartWriter draws the charts of `prism speedup` and `sweep`; both are
// empty in a build without Qt.
int runCli(int argc, char** argv, MpiSession* session = nullptr, const ViewerRunner& viewer = {},
           const ChartWriter& chartWriter = {});

}  // namespace prism

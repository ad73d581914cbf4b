// The `prism` command line: subcommands, their options and their help. Every rank of an MPI run
// parses the same arguments; main (the composition root) then decides the rank's role.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "cluster/DistributionOptions.h"
#include "master/analysis/SpeedupChart.h"
#include "master/commands/ViewCommand.h"

namespace prism {

class Transport;

struct ParsedCommand {
  bool exitNow = false;  // help, version, the command list or a usage error: nothing to run
  int exitCode = 0;
  // What a slave needs of the command line: its threads, its memory limit (each rank its own:
  // nodes differ) and, in tests, its fault.
  DistributionOptions distribution;
  std::optional<uint64_t> memoryLimit;
  // Runs the command on rank 0 or the only process (session null); returns the exit code.
  std::function<int(Transport* session)> runMaster;
};

// Parses argv. quiet: print nothing (a slave rank; rank 0 prints help and usage errors). viewer
// runs `prism view` and chartWriter draws the charts of `prism speedup` and `sweep`; both are
// empty in a build without Qt.
ParsedCommand parseCommandLine(int argc, char** argv, bool quiet, const ViewerRunner& viewer = {},
                               const ChartWriter& chartWriter = {});

}  // namespace prism

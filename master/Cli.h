// The `prism` command line: subcommands, their options and their help.
#pragma once

#include <string>
#include <vector>

namespace prism {

// Parses argv and runs the chosen subcommand; returns the process exit code.
int runCli(int argc, char** argv);

}  // namespace prism

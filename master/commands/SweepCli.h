// The `prism sweep` command's options and help (Cli.cpp holds the other commands).
#pragma once

#include "master/commands/SweepCommand.h"

namespace CLI {
class App;
}

namespace prism {

void addSweepCommand(CLI::App& app, SweepOptions& o);

}  // namespace prism

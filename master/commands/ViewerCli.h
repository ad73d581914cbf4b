// The command-line options of the viewer window, which `prism view` and `prism connect` share,
// of serving (`prism view --serve`), and the `connect` command (Cli.cpp holds the rest).
#pragma once

#include "master/commands/ConnectCommand.h"
#include "master/live/ViewerOptions.h"
#include "master/remote/ServeOptions.h"

namespace CLI {
class App;
}

namespace prism {

void addViewerWindowOptions(CLI::App* command, ViewerOptions& o);
void addServeOptions(CLI::App* command, ServeOptions& o);
CLI::App* addConnectCommand(CLI::App& app, ConnectCommandOptions& o);

}  // namespace prism

#include "master/commands/ViewerCli.h"

#include <CLI/CLI.hpp>
#include <cctype>

namespace prism {

void addViewerWindowOptions(CLI::App* command, ViewerOptions& o) {
  command
      ->add_option("--speedup-csv", o.speedupCsv,
                   "Speedup table (columns p,seconds,speedup,efficiency) to chart at start")
      ->check(CLI::ExistingFile);
  command
      ->add_option("--exit-after-passes", o.exitAfterPasses,
                   "Quit once this many full passes of the view asked for last are done; that "
                   "view renders no more (scripts: with --save, exactly this many passes)")
      ->check(CLI::Range(1, 1 << 20));
  command->add_option("--save", o.savePath,
                      "Save the image here (.png or .exr) when the viewer quits (written where "
                      "the window is; an EXR holds the full-precision pixels)");
  command->add_option("--screenshot", o.screenshotPath,
                      "Save a picture of the whole window (.png) after --screenshot-after, then "
                      "quit");
  command
      ->add_option("--keys", o.keys,
                   "Type these keys into the window at start, in order, as if pressed (scripts "
                   "and screenshots), e.g. --keys C for the caustic map or --keys bC")
      ->check([](const std::string& keys) {
        for (const char c : keys) {
          if (!std::isalpha(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '=') {
            return std::string("only letters and + - = can be typed, not '") + c + "'";
          }
        }
        return std::string();
      });
  command
      ->add_option("--screenshot-after", o.screenshotSeconds,
                   "Seconds after start for --screenshot (default 2)")
      ->check(CLI::Range(0.0, 3600.0));
  command
      ->add_option("--benchmark-moves", o.benchmarkMoves,
                   "Once the first full image is shown, orbit the camera N times, one move every "
                   "--benchmark-interval ms; print the frame rate and frame times while moving "
                   "(a 'realtime' line for scripts) and the time to full resolution, then quit")
      ->check(CLI::Range(1, 100000));
  command
      ->add_option("--benchmark-interval", o.benchmarkMoveMilliseconds,
                   "Milliseconds between --benchmark-moves moves (default 10, a mouse drag's "
                   "event rate)")
      ->check(CLI::Range(1.0, 10000.0));
}

void addServeOptions(CLI::App* command, ServeOptions& o) {
  command
      ->add_option("--serve", o.address,
                   "Show no window: serve the live session on [HOST:]PORT (default host "
                   "127.0.0.1; PORT 0 picks a free one) for `prism connect`. Reach it from a "
                   "desk through `ssh -L`; see docs/distributed.md")
      ->option_text("[HOST:]PORT");
  command->add_option("--connection-file", o.connectionFile,
                      "With --serve: write host, port and token here (mode 0600) for "
                      "`prism connect FILE`; removed when the job ends");
  command->add_flag("--exit-with-client", o.exitWithClient,
                    "With --serve: end the job when the connected viewer leaves");
  command->add_flag("--allow-network", o.allowNetwork,
                    "With --serve: allow an address beyond this machine (anyone who reaches the "
                    "port may try the token; prefer 127.0.0.1 and an SSH tunnel)");
  command
      ->add_option("--client-timeout", o.clientTimeoutSeconds,
                   "With --serve: drop a viewer silent or not reading for this many seconds "
                   "(default 10)")
      ->check(CLI::Range(1.0, 3600.0));
}

CLI::App* addConnectCommand(CLI::App& app, ConnectCommandOptions& o) {
  CLI::App* connect = app.add_subcommand(
      "connect",
      "Open the viewer on a job that serves its live session (prism view --serve).\n"
      "The same window, keys and statistics as `prism view`; images are saved here.\n"
      "TARGET is the job's connection file, or HOST:PORT with the token in --token-file or\n"
      "PRISM_TOKEN (never on the command line). See docs/viewer.md.");
  connect->add_option("target", o.target, "Connection file, or HOST:PORT")->required();
  connect->add_option("--token-file", o.tokenFile,
                      "With HOST:PORT: a file whose first line is the job's token (else "
                      "$PRISM_TOKEN)");
  connect
      ->add_option("--timeout", o.timeoutSeconds,
                   "Seconds to wait for the job to answer (default 10)")
      ->check(CLI::Range(0.1, 600.0));
  connect
      ->add_option("--frame-time", o.window.frameTimeMilliseconds,
                   "Ask the job for this frame time while the camera moves, in ms (default: the "
                   "job's --frame-time); 0: no target, always full resolution")
      ->check(CLI::Range(0.0, 60000.0));
  addViewerWindowOptions(connect, o.window);
  return connect;
}

}  // namespace prism

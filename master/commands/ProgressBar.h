// A one-line progress bar on stderr, redrawn in place, for terminals only: when stderr is not
// a terminal (logs, CI) it stays silent so output files are not filled with redraws.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "util/Stopwatch.h"

namespace prism {

class ProgressBar {
 public:
  ProgressBar(std::string label, size_t total, std::string unit, bool enabled);
  ~ProgressBar();

  void update(size_t done);
  // For work whose size is known only once it starts; elapsed time still counts from creation.
  void setTotal(size_t total) { total_ = total; }
  // Draws the final state and ends the line.
  void finish();

  // The text of the bar for the given state, for a terminal `columns` wide (tested directly).
  static std::string format(const std::string& label, size_t done, size_t total,
                            const std::string& unit, double elapsedSeconds, int columns);

 private:
  std::string label_;
  size_t total_;
  std::string unit_;
  bool enabled_;
  bool finished_ = false;
  SteadyClock::time_point start_;
};

// A bar per stage of a run ("trace photons", "render", "pass 2/8", ...): a stage's first
// report ends the bar before it and starts its own. As PassProgress (master/frame/
// CausticPasses.h) wants it.
class StageProgress {
 public:
  explicit StageProgress(bool enabled) : enabled_(enabled) {}
  void operator()(const std::string& stage, size_t done, size_t total);
  void finish() {
    if (bar_) bar_->finish();
  }

 private:
  bool enabled_;
  std::string stage_;
  std::unique_ptr<ProgressBar> bar_;
};

// Whether stderr is an interactive terminal.
bool stderrIsTerminal();

}  // namespace prism

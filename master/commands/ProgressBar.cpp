#include "master/commands/ProgressBar.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace prism {
namespace {

int terminalColumns() {
  winsize size{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return 80;
}

std::string formatSeconds(double s) {
  char text[32];
  if (s < 60.0) {
    std::snprintf(text, sizeof text, "%.1fs", s);
  } else {
    std::snprintf(text, sizeof text, "%dm%02ds", static_cast<int>(s / 60.0),
                  static_cast<int>(s) % 60);
  }
  return text;
}

}  // namespace

bool stderrIsTerminal() {
  return ::isatty(STDERR_FILENO) == 1;
}

ProgressBar::ProgressBar(std::string label, size_t total, std::string unit, bool enabled)
    : label_(std::move(label)),
      total_(total),
      unit_(std::move(unit)),
      enabled_(enabled && stderrIsTerminal()),
      start_(SteadyClock::now()) {}

ProgressBar::~ProgressBar() {
  if (enabled_ && !finished_) std::fputs("\n", stderr);
}

std::string ProgressBar::format(const std::string& label, size_t done, size_t total,
                                const std::string& unit, double elapsedSeconds, int columns) {
  const double fraction = total > 0 ? std::min(1.0, static_cast<double>(done) / total) : 1.0;
  std::string tail = " " + std::to_string(static_cast<int>(fraction * 100.0)) + "% " +
                     std::to_string(done) + "/" + std::to_string(total) + " " + unit + " " +
                     formatSeconds(elapsedSeconds);
  if (done > 0 && done < total) {
    tail += " ETA " + formatSeconds(elapsedSeconds * (1.0 - fraction) / fraction);
  }
  const int barWidth = std::max(10, columns - static_cast<int>(label.size() + tail.size()) - 4);
  const int filled = static_cast<int>(fraction * barWidth);
  return label + " [" + std::string(filled, '#') + std::string(barWidth - filled, '.') + "]" + tail;
}

void ProgressBar::update(size_t done) {
  if (!enabled_) return;
  const double elapsed = secondsSince(start_);
  const std::string line = format(label_, done, total_, unit_, elapsed, terminalColumns() - 1);
  std::fprintf(stderr, "\r%s\033[K", line.c_str());
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (!enabled_ || finished_) return;
  update(total_);
  std::fputs("\n", stderr);
  finished_ = true;
}

void StageProgress::operator()(const std::string& stage, size_t done, size_t total) {
  if (!enabled_) return;
  if (!bar_ || stage != stage_) {
    if (bar_) bar_->finish();
    bar_ = std::make_unique<ProgressBar>(stage, total, "tiles", true);
    stage_ = stage;
  }
  bar_->setTotal(total);
  bar_->update(done);
}

}  // namespace prism

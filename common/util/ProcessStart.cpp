#include "util/ProcessStart.h"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

namespace prism {
namespace {

// Field 22 of /proc/PID/stat: the start time in clock ticks since boot. The command name (field
// 2) may hold spaces and parentheses, so fields are counted from its closing parenthesis.
std::optional<double> startSecondsAfterBoot(const std::string& pid) {
  std::ifstream in("/proc/" + pid + "/stat");
  std::string line;
  if (!std::getline(in, line)) return std::nullopt;
  const size_t close = line.rfind(')');
  if (close == std::string::npos) return std::nullopt;
  std::istringstream fields(line.substr(close + 1));
  std::string field;
  for (int i = 3; i <= 22; ++i) {
    if (!(fields >> field)) return std::nullopt;
  }
  const long ticksPerSecond = ::sysconf(_SC_CLK_TCK);
  if (ticksPerSecond <= 0) return std::nullopt;
  return std::stod(field) / static_cast<double>(ticksPerSecond);
}

std::optional<double> secondsSinceBoot() {
  std::ifstream in("/proc/uptime");
  double seconds = 0.0;
  if (!(in >> seconds)) return std::nullopt;
  return seconds;
}

}  // namespace

std::optional<double> secondsSinceProcessStart() {
  const std::optional<double> now = secondsSinceBoot();
  const std::optional<double> start = startSecondsAfterBoot("self");
  if (!now || !start) return std::nullopt;
  return *now - *start;
}

std::optional<double> secondsFromParentStart() {
  const std::optional<double> parent = startSecondsAfterBoot(std::to_string(::getppid()));
  const std::optional<double> self = startSecondsAfterBoot("self");
  if (!parent || !self) return std::nullopt;
  return *self - *parent;
}

}  // namespace prism

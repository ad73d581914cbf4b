#include "util/MemorySize.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace prism {

uint64_t parseMemorySize(const std::string& text) {
  const auto invalid = [&] {
    return std::invalid_argument("--memory-limit: '" + text +
                                 "' is not a size (examples: 512M, 8G, 1.5T, 1000000)");
  };
  size_t end = 0;
  double number = 0.0;
  try {
    number = std::stod(text, &end);
  } catch (const std::exception&) {
    throw invalid();
  }
  std::string unit;
  for (size_t i = end; i < text.size(); ++i) {
    if (text[i] != ' ')
      unit += static_cast<char>(std::toupper(static_cast<unsigned char>(text[i])));
  }
  if (unit.size() > 1 && (unit.substr(1) == "B" || unit.substr(1) == "IB")) unit.resize(1);
  const std::string units = "BKMGTPE";
  const size_t power = unit.empty() ? 0 : units.find(unit);
  if (unit.size() > 1 || power == std::string::npos || !(number > 0.0) || !std::isfinite(number)) {
    throw invalid();
  }
  const double bytes = number * std::pow(1024.0, static_cast<double>(power));
  if (bytes >= 1.8e19) return std::numeric_limits<uint64_t>::max();
  if (bytes < 1.0) throw invalid();
  return static_cast<uint64_t>(bytes);
}

std::string formatBytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int unit = 0;
  while (bytes >= 1024.0 && unit < 6) {
    bytes /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", bytes, units[unit]);
  return text;
}

std::string memoryRefusal(const std::string& what, uint64_t needed, const MemoryLimit& limit,
                          const std::string& hint) {
  return what + " needs " + formatBytes(static_cast<double>(needed)) + " (" +
         std::to_string(needed) + " bytes); the memory limit is " +
         formatBytes(static_cast<double>(limit.bytes)) + " (" + std::to_string(limit.bytes) +
         " bytes, " + limit.source + "): " + hint;
}

uint64_t saturatingMultiply(uint64_t a, uint64_t b) {
  if (a != 0 && b > std::numeric_limits<uint64_t>::max() / a) {
    return std::numeric_limits<uint64_t>::max();
  }
  return a * b;
}

uint64_t saturatingAdd(uint64_t a, uint64_t b) {
  return b > std::numeric_limits<uint64_t>::max() - a ? std::numeric_limits<uint64_t>::max()
                                                      : a + b;
}

}  // namespace prism

// Numbers as text for reports and CSV files.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace prism {

// printf-style formatting of one number.
inline std::string formatNumber(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

// Empty for an undefined value (NaN or infinite), so a CSV has no "nan" in it.
inline std::string csvNumber(double value, const char* pattern = "%.6g") {
  return std::isfinite(value) ? formatNumber(pattern, value) : std::string();
}

}  // namespace prism

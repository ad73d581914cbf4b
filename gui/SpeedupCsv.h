// The speedup table the statistics panel charts: a CSV file with a header line naming at least
// the columns p, seconds, speedup and efficiency (in any order; other columns are ignored),
// then one row per process count. Lines starting with # and blank lines are skipped. When a
// `series` column is present (`prism speedup` writes one series per schedule and tile size),
// only the rows of the first series are read. This is the format `prism speedup` writes;
// docs/viewer.md and docs/scaling.md describe it. No Qt.
#pragma once

#include <string>
#include <vector>

namespace prism {

struct SpeedupPoint {
  int processes = 0;
  double seconds = 0.0;
  double speedup = 0.0;
  double efficiency = 0.0;
};

// Throws std::runtime_error "file:line: what is wrong".
std::vector<SpeedupPoint> readSpeedupCsv(const std::string& path);
std::vector<SpeedupPoint> parseSpeedupCsv(const std::string& text, const std::string& name);

}  // namespace prism

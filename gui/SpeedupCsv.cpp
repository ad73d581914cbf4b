#include "gui/SpeedupCsv.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace prism {
namespace {

std::vector<std::string> splitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) {
    const auto first = field.find_first_not_of(" \t\r");
    const auto last = field.find_last_not_of(" \t\r");
    fields.push_back(first == std::string::npos ? "" : field.substr(first, last - first + 1));
  }
  return fields;
}

double toNumber(const std::string& text, const std::string& where, const char* column) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value) || value < 0.0) {
    throw std::runtime_error(where + ": " + column + " '" + text +
                             "' is not a non-negative number");
  }
  return value;
}

}  // namespace

std::vector<SpeedupPoint> parseSpeedupCsv(const std::string& text, const std::string& name) {
  static constexpr std::array<const char*, 4> kColumns = {"p", "seconds", "speedup", "efficiency"};
  std::stringstream in(text);
  std::string line;
  int lineNumber = 0;
  std::array<int, 4> column{-1, -1, -1, -1};
  int seriesColumn = -1;  // optional: `prism speedup` writes several series in one file
  std::string firstSeries;
  bool haveHeader = false;
  std::vector<SpeedupPoint> points;
  while (std::getline(in, line)) {
    ++lineNumber;
    const std::string where = name + ":" + std::to_string(lineNumber);
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    const std::vector<std::string> fields = splitFields(line);
    if (!haveHeader) {
      for (size_t c = 0; c < kColumns.size(); ++c) {
        const auto it = std::find(fields.begin(), fields.end(), kColumns[c]);
        if (it == fields.end()) {
          throw std::runtime_error(where + ": the header has no column '" +
                                   std::string(kColumns[c]) +
                                   "' (expected p,seconds,speedup,efficiency)");
        }
        column[c] = static_cast<int>(it - fields.begin());
      }
      const auto series = std::find(fields.begin(), fields.end(), "series");
      if (series != fields.end()) seriesColumn = static_cast<int>(series - fields.begin());
      haveHeader = true;
      continue;
    }
    if (seriesColumn >= 0 && seriesColumn < static_cast<int>(fields.size())) {
      if (points.empty() && firstSeries.empty()) firstSeries = fields[seriesColumn];
      if (fields[seriesColumn] != firstSeries) continue;  // one curve: the first series
    }
    const int needed = *std::max_element(column.begin(), column.end()) + 1;
    if (static_cast<int>(fields.size()) < needed) {
      throw std::runtime_error(where + ": " + std::to_string(fields.size()) +
                               " fields, the header names " + std::to_string(needed));
    }
    SpeedupPoint p;
    const double processes = toNumber(fields[column[0]], where, "p");
    if (processes < 1.0 || processes != std::floor(processes) || processes > 1e6) {
      throw std::runtime_error(where + ": p '" + fields[column[0]] +
                               "' is not a whole number of processes");
    }
    p.processes = static_cast<int>(processes);
    p.seconds = toNumber(fields[column[1]], where, "seconds");
    p.speedup = toNumber(fields[column[2]], where, "speedup");
    p.efficiency = toNumber(fields[column[3]], where, "efficiency");
    points.push_back(p);
  }
  if (!haveHeader) throw std::runtime_error(name + ": empty; expected a header line");
  if (points.empty()) throw std::runtime_error(name + ": a header but no rows");
  std::sort(points.begin(), points.end(),
            [](const SpeedupPoint& a, const SpeedupPoint& b) { return a.processes < b.processes; });
  return points;
}

std::vector<SpeedupPoint> readSpeedupCsv(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error(path + ": cannot open");
  std::stringstream text;
  text << file.rdbuf();
  return parseSpeedupCsv(text.str(), path);
}

}  // namespace prism

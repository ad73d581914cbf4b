// Text outputs (CSV files, reports) written through a temporary name in the same folder and
// renamed on success, so an interrupted or failed write never leaves a half-written file.
#pragma once

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace prism {

// write(std::ostream&) fills the file. Throws std::runtime_error naming the path.
template <typename Write>
void writeFileAtomically(const std::string& path, Write write) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream file(temporary);
    if (!file) throw std::runtime_error("cannot write " + path);
    write(file);
    if (!file.flush()) throw std::runtime_error("cannot write " + path);
  }
  std::filesystem::rename(temporary, path);
}

}  // namespace prism

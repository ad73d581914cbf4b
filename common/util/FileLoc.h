// A position in a scene file. Every parsed entity keeps one so errors can say file:line:col.
#pragma once

#include <stdexcept>
#include <string>

namespace prism {

struct FileLoc {
  std::string file;
  int line = 0;    // 1-based; 0 when unknown
  int column = 0;  // 1-based; 0 when unknown

  std::string toString() const {
    if (line <= 0) return file;
    return file + ":" + std::to_string(line) + ":" + std::to_string(column > 0 ? column : 1);
  }
};

// Thrown by every parser and loader for bad input; what() reads "file:line:col: message".
class SceneError : public std::runtime_error {
 public:
  SceneError(const FileLoc& loc, const std::string& message)
      : std::runtime_error(loc.toString() + ": " + message), loc_(loc), message_(message) {}

  const FileLoc& loc() const { return loc_; }
  const std::string& message() const { return message_; }

 private:
  FileLoc loc_;
  std::string message_;
};

}  // namespace prism

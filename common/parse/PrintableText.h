// Quoting words from an input file in error messages.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace prism {

// The word as it may safely appear in a message: at most maxShown bytes (then "..."), with every
// byte outside printable ASCII, and the backslash, written as \xNN. A binary file fed to a parser
// must not produce a huge or garbled message.
inline std::string printableExcerpt(std::string_view word, size_t maxShown = 24) {
  std::string shown;
  for (size_t i = 0; i < word.size() && i < maxShown; ++i) {
    const auto c = static_cast<unsigned char>(word[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      shown += static_cast<char>(c);
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
      shown += escaped;
    }
  }
  if (word.size() > maxShown) shown += "...";
  return shown;
}

}  // namespace prism

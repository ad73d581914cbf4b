#include "scene/SettingNames.h"

#include <cctype>

namespace prism {

std::string normalisedName(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    c = c == '-' ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

}  // namespace prism

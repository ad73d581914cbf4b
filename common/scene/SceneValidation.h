// The one check that a scene description's settings can be rendered: every bounded setting
// within its SettingLimits.h range, every real-valued one in its domain. The parsers call it
// after reading, the codec after decoding, and `prism` after applying command-line overrides,
// so a value is refused the same way whichever route it came by.
#pragma once

#include <stdexcept>

#include "scene/SceneDescription.h"

namespace prism {

// What validate() throws: "render setting 'max_depth' must be at most 256, found 300
// (--max-depth on the command line)".
class SettingError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

void validate(const RenderSettings& settings);
void validate(const CausticSettings& caustics);
void validate(const SceneDescription& description);  // its render and caustics settings

}  // namespace prism

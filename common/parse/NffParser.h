// Eric Haines' Neutral File Format (the SPD scenes).
#pragma once

#include <string>

#include "scene/SceneDescription.h"

namespace prism {

// Parses NFF text. path names the file in error messages. Throws SceneError on bad input.
SceneDescription parseNff(const std::string& text, const std::string& path);

}  // namespace prism

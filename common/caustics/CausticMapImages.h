// Debug pictures of a caustic map, each view side by side: receiver positions and caster
// positions (mapped into the unit cube over the texels' bounds), caster normals (n/2 + 1/2) and
// the caustic irradiance (scaled so the 99.5th percentile of the lit texels is 1; brighter ones
// exceed 1 and show white). Empty texels are black.
#pragma once

#include <string>
#include <vector>

#include "caustics/CausticMap.h"
#include "image/ImageRgb.h"

namespace prism {

inline constexpr double kCausticWhitePercentile = 0.995;

struct NamedImage {
  std::string name;  // receivers, casters, normals, caustics
  ImageRgb image;
};

std::vector<NamedImage> causticMapImages(const CausticMap& map);

}  // namespace prism

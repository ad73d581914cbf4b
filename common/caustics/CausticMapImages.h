// Debug pictures of a caustic map, each view side by side: receiver positions and caster
// positions (mapped into the unit cube over the scene's bounds), caster normals (n/2 + 1/2) and
// the caustic irradiance (scaled so the brightest texel is 1). Empty texels are black.
#pragma once

#include <string>
#include <vector>

#include "caustics/CausticMap.h"
#include "image/ImageRgb.h"

namespace prism {

struct NamedImage {
  std::string name;  // receivers, casters, normals, caustics
  ImageRgb image;
};

std::vector<NamedImage> causticMapImages(const CausticMap& map);

}  // namespace prism

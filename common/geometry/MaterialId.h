// The index of a material in SceneDescription::materials. Primitives and hits carry it, so it
// lives with the geometry, below the scene description that defines the materials.
#pragma once

#include <cstdint>

namespace prism {

using MaterialId = uint32_t;

}  // namespace prism

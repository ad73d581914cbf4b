// Refuses absurd requests before any work starts, saying what they would need.
#pragma once

#include <cstdint>
#include <string>

#include "scene/SceneDescription.h"

namespace prism {

// Bytes a render of these settings needs at least: the frame buffer and, at worst, every tile
// result in flight at once.
uint64_t frameMemoryBytes(const RenderSettings& settings);

// Physical memory of this machine in bytes.
uint64_t physicalMemoryBytes();

// Throws std::runtime_error when the render cannot fit: the message names the size needed and
// the memory available.
void checkRenderFits(const RenderSettings& settings, uint64_t availableBytes);

// "1.5 GiB", "312 KiB", ...
std::string formatBytes(double bytes);

}  // namespace prism

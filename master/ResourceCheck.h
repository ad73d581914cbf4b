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

// Bytes a photon pass of these settings may need on rank 0 at worst (every photon stored): the
// shares as they arrive, the assembled map with its kd-tree, and the message that sends it on.
uint64_t photonMemoryBytes(const CausticSettings& caustics);

// Throws std::runtime_error when the photon map cannot fit, naming the bytes and the memory.
void checkCausticsFit(const CausticSettings& caustics, uint64_t availableBytes);

// "1.5 GiB", "312 KiB", ...
std::string formatBytes(double bytes);

}  // namespace prism

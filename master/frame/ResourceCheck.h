// Refuses absurd requests before any work starts, saying what they would need. Every check
// compares an estimate of the bytes a part of the run needs with the run's memory limit
// (--memory-limit, default the machine's physical memory) and throws ResourceLimitError with
// the bytes and the limit; where memory is not what runs out (the tile count) a fixed bound
// applies. The bounds of the settings themselves (samples per pixel, recursion depth, ...) are
// scene/SettingLimits.h, checked by validate(). docs/reliability.md, "Limits", gives the formulas.
#pragma once

#include <cstdint>
#include <string>

#include "scene/GeometryMemory.h"
#include "scene/SceneDescription.h"
#include "util/MemorySize.h"
#include "util/PhysicalMemory.h"

namespace prism {

inline constexpr uint64_t kMaxTileCount = 1u << 24;  // tile indices and job counts stay small

// Bytes a render of these settings needs at least: the frame buffer and, at worst, every tile
// result in flight at once: 2 · width · height · 12.
uint64_t frameMemoryBytes(const RenderSettings& settings);

// Throws when the frame buffer cannot fit.
void checkRenderFits(const RenderSettings& settings, const MemoryLimit& limit);

// Tiles of a frame with this tile edge (0: automatic, at most as many as 8-pixel tiles).
uint64_t tileCount(const RenderSettings& settings, int tileSize);
// Bytes of per-tile bookkeeping on rank 0 (plan, scheduler, frame buffer flags): 64 per tile.
uint64_t tileMemoryBytes(uint64_t tiles);
// Throws past kMaxTileCount tiles or when their bookkeeping cannot fit.
void checkTilesFit(const RenderSettings& settings, int tileSize, const MemoryLimit& limit);

// Bytes a photon pass of these settings may need on rank 0 at worst (every photon stored): the
// shares as they arrive, the assembled map with its kd-tree, and the message that sends it on.
uint64_t photonMemoryBytes(const CausticSettings& caustics);

// Bytes the caustic maps of `lights` point lights need at least: one view a light (a light
// among its casters takes six, which only the built scene tells: caustics/CausticMapMemory.h
// checks that on every rank), each texel with its receiver, caster and lookup records and the
// build's flux and blur buffers. Requests past the limit even so are refused before the scene
// is sent or built.
uint64_t causticMapMemoryBytes(const CausticSettings& caustics, size_t lights);

// Throws when the photon map, or the caustic maps of `lights` lights, cannot fit, naming the
// bytes and the limit.
void checkCausticsFit(const CausticSettings& caustics, size_t lights, const MemoryLimit& limit);

// Throws when the geometry cannot fit, and then when everything together cannot (caustic maps
// counted at their worst).
void checkSceneFits(const SceneDescription& description, int tileSize, const MemoryLimit& limit);

}  // namespace prism

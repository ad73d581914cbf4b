// The tile renderer of one instruction set: where TileRenderer::render goes. The whole render
// path of a tile (camera rays, the integrator, the shading lanes) is compiled once per set, like
// the geometry kernels it calls (accel/GeometryKernels.h; CMakeLists.txt, "Kernels per
// instruction set"), so the shading arithmetic gets the set's vectors too.
#pragma once

#include <atomic>
#include <cstdint>

#include "render/Tile.h"
#include "util/InstructionSet.h"

namespace prism {

class TileRenderer;

struct RenderKernels {
  InstructionSet instructionSet;
  TileResult (*renderTile)(const TileRenderer&, uint32_t tileIndex, const TileRect& rect,
                           const std::atomic<bool>* cancel, const std::atomic<bool>* frameEnded);
};

// The kernels compiled for isa, a concrete set this binary holds.
const RenderKernels& renderKernels(InstructionSet isa);

}  // namespace prism

// One pass of a frame: its number and the light terms its tiles add up. A plain render is one
// pass with direct light (and photon-mapped caustics when the scene has them); a progressive
// render is a direct pass followed by caustic-only passes, each with its own photon map. Tile
// jobs hold the pass by shared pointer, so its photon map lives as long as a tile needs it.
#pragma once

#include <cstdint>
#include <memory>

#include "caustics/CausticEstimator.h"
#include "render/LightTerms.h"

namespace prism {

struct RenderPass {
  uint32_t index = 0;
  bool direct = true;
  std::shared_ptr<const CausticEstimator> caustics;  // null: no caustic term
  // The caustics come from caustic maps each rank builds from the scene (nothing is sent),
  // not from a photon map the master sends.
  bool causticMap = false;

  LightTerms terms() const { return {direct, caustics.get()}; }
};

}  // namespace prism

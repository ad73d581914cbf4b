// One pass of a frame: its number and the light terms its tiles add up. A plain render is one
// pass with direct light (and caustics when the scene has them); a progressive render is a
// direct pass followed by caustic-only passes, each with its own photon map. Tile jobs hold the
// pass by shared pointer, so its photon map lives as long as a tile needs it.
//
// The light terms are decided here, once: rank 0 makes its passes with the factories below, the
// wire carries their terms (wire/TileJobWire.h), and a slave makes the same pass from them with
// the same factories and the caustics it holds for that pass.
#pragma once

#include <cstdint>
#include <memory>

#include "caustics/CausticEstimator.h"
#include "render/LightTerms.h"

namespace prism {

class CausticMapEstimator;  // caustics/CausticMapEstimator.h: not for the wire to reach

// Where a pass's caustics come from.
enum class CausticSource : uint8_t {
  None,
  PhotonMap,   // a photon map rank 0 traced with the slaves and sent to each of them
  CausticMap,  // caustic maps each rank builds from the scene itself (nothing is sent)
};

struct RenderPass {
  uint32_t index = 0;
  bool direct = true;
  std::shared_ptr<const CausticEstimator> caustics;  // null: no caustic term
  CausticSource source = CausticSource::None;

  LightTerms terms() const { return {direct, caustics.get()}; }

  // Direct light alone.
  static std::shared_ptr<const RenderPass> directOnly(uint32_t index);
  // Direct light (or not: a progressive caustic pass) and the caustics gathered from a photon
  // map; direct light alone without one.
  static std::shared_ptr<const RenderPass> withPhotons(
      uint32_t index, bool direct, std::shared_ptr<const CausticEstimator> gather);
  // Direct light and the caustics of the caustic maps; direct light alone when the maps are
  // empty (no light reaches a caster).
  static std::shared_ptr<const RenderPass> withCausticMaps(
      uint32_t index, std::shared_ptr<const CausticMapEstimator> maps);
};

}  // namespace prism

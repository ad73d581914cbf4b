// Direct light from a point light for the shading points of a packet, all at once
// (render/ShadingLanes.h): the path to the light, the shadow ray's origin and length and the
// surface's reflectance take one vector operation each instead of one per point. Lane by lane
// the arithmetic is render/PointLightPath.h's towardsLight(), reflectance() and
// lightReflected(), so every lane's answer is the scalar one to the bit; only pow() is taken
// lane by lane (the library's own).
#pragma once

#include <cstdint>

#include "math/Ray.h"
#include "render/ShadingLanes.h"
#include "scene/SceneDescription.h"

namespace prism {

// One light's paths from the lanes, once they are known to reach it.
struct LightPathLanes {
  alignas(32) ShadingLanes::Lanes distance, reflectance[3];
  uint32_t towards = 0;  // lanes that trace a shadow ray: the light reaches them and adds something
};

// For the lanes in `lanes`: which ones the light can reach (not behind the surface, not at it)
// and what the surface reflects of it towards the viewer; lanes where that reflectance is
// exactly zero (a mirror's highlight turned away or underflowing) are left out of
// `paths.towards` like unreachable ones. Writes shadows[i] for every lane i of paths.towards and
// makes every other lane below `count` an empty ray (tMin 0, tMax -1; its other fields are not
// written).
void lightPathLanes(const ShadingLanes& s, uint32_t lanes, int count, const PointLightDesc& light,
                    LightPathLanes& paths, Ray* shadows);

// Adds the light's reflected radiance to `direct` in the lanes of `unblocked` (a subset of
// paths.towards whose shadow rays met nothing); the other lanes keep their values.
void addLightLanes(const LightPathLanes& paths, uint32_t unblocked, const PointLightDesc& light,
                   ShadingLanes::Lanes direct[3]);

}  // namespace prism

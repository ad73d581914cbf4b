// The mirror rays of a packet's shading points, all at once (render/ShadingLanes.h): each point's
// reflected direction (shading/SpecularSplit.h's reflectedDirection: about the shading normal,
// or about the geometric one where that would send it below the surface) and its origin just off
// the surface (SurfaceHit::rayOrigin), one vector operation for every point where the scalar
// code takes one per point. Lane by lane the same arithmetic, so the same rays to the bit.
#pragma once

#include "math/Ray.h"
#include "render/ShadingLanes.h"

namespace prism {

// rays[i] = Ray{origin, direction} of lane i's mirror ray (tMin 0, no end), for all
// ShadingLanes::kLanes lanes: the caller keeps the lanes it bounces and empties the others. The
// incoming direction of each lane is -s.toViewer.
void mirrorRayLanes(const ShadingLanes& s, Ray* rays);

}  // namespace prism

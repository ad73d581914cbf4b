// The photon gather radius: the k-NN cap a scene gets when it leaves it at 0, and the gather of
// each progressive pass. Pure functions of the scene's settings and the pass number, shared by
// the frame renderer, the viewer and the tests.
#pragma once

#include "caustics/PhotonGatherSettings.h"
#include "scene/Scene.h"

namespace prism {

// The k-NN gather radius cap when the scene leaves it at 0: a tenth of the largest bounded
// caster's bounding radius, or a hundredth of the scene's size when only planes cast.
float automaticMaxRadius(const Scene& scene);

// The gather of classic photon mapping: per-photon radii of the scene's k (or, with gather: auto,
// each photon's own k up to the noise's largest k), capped at maxRadius.
PhotonGatherSettings classicGather(const CausticSettings& c, float maxRadius);

// The progressive gather radius of pass `pass` ≥ 2, given pass − 1's:
// r²(pass) = r²(pass − 1)·(pass − 1 + α)/pass.
float nextProgressiveRadius(float previous, int pass, float alpha);

// The gather of progressive pass `pass` ≥ 1 (`previous` is pass − 1's, unused for pass 1).
// With the scene's `radius` set: that one fixed radius for every photon, shrunk by the rule
// above from pass to pass (Knaus & Zwicker 2011). Left at 0 (the default): per-photon radii,
// each photon's distance to its k-th nearest photon of its own pass (capped at maxRadius) —
// the local density, so narrow at a focus or a fold and wide in the dim halo — all shrunk by
// the same rule as the pass count grows. Pass 1 is then the classic estimate exactly.
PhotonGatherSettings progressiveGather(const CausticSettings& c, float maxRadius, int pass,
                                       const PhotonGatherSettings& previous);

}  // namespace prism

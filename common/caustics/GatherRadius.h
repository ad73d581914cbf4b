// The photon gather radius: the k-NN cap a scene gets when it leaves it at 0, and the fixed
// radius of each progressive pass (Knaus & Zwicker 2011). Pure functions of the scene and the
// photon map, shared by the frame renderer, the viewer and the tests.
#pragma once

#include "caustics/PhotonMap.h"
#include "scene/Scene.h"

namespace prism {

// The k-NN gather radius cap when the scene leaves it at 0: a tenth of the largest bounded
// caster's bounding radius, or a hundredth of the scene's size when only planes cast.
float automaticMaxRadius(const Scene& scene);

// The first progressive radius when the scene leaves it at 0: the mean distance from a spread
// of stored photons to their k-th nearest neighbour, capped at maxRadius.
float automaticProgressiveRadius(const PhotonMap& map, int k, float maxRadius);

// The progressive gather radius of pass `pass` ≥ 2, given pass − 1's:
// r²(pass) = r²(pass − 1)·(pass − 1 + α)/pass.
float nextProgressiveRadius(float previous, int pass, float alpha);

}  // namespace prism

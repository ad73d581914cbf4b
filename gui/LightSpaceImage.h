// Caustic mapping's debug views (Shah et al. 2007), as the viewer shows them on R, P and C: the
// light-space maps of every light that has one (common/caustics/CausticMapImages.h), each
// light's views side by side and the lights one above the other, display-encoded like
// `prism render --caustic-map-debug`.
#pragma once

#include <QImage>
#include <QString>

#include "caustics/CausticMapEstimator.h"

namespace prism {

enum class LightSpaceMap {
  Casters,    // R: caster (refractive/reflective) surface positions
  Receivers,  // P: receiver surface positions
  Caustics,   // C: caustic irradiance, brightest texel white
};

// A null image when there are no maps (no light sees a caster).
QImage lightSpaceImage(const CausticMapEstimator& maps, LightSpaceMap which);

// "caustic map (C) · light space, 2 light(s), 2 view(s) of 512x512 texels · blur on (b) · …".
QString lightSpaceCaption(const CausticMapEstimator& maps, LightSpaceMap which, bool blur);

}  // namespace prism

// A debug picture of a photon map: every stored photon projected through the camera (hidden or
// not) and its power added to the pixel it lands in, scaled so the brightest 1 % of lit pixels
// saturate. It shows where photons landed and how densely, not what the image will look like.
#pragma once

#include "caustics/PhotonMap.h"
#include "image/ImageRgb.h"
#include "scene/Camera.h"

namespace prism {

ImageRgb photonImage(const PhotonMap& map, const Camera& camera, int width, int height);

}  // namespace prism

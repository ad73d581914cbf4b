// Which parts of the light a render adds up. Progressive caustics render the direct part once
// and the caustic part once per pass, then sum them. Apart from the integrator so that tile
// jobs and the wire can name a pass's terms without the scene and its BVH.
#pragma once

#include "caustics/CausticEstimator.h"

namespace prism {

struct LightTerms {
  bool direct = true;                          // ambient, lights through shadow rays, environment
  const CausticEstimator* caustics = nullptr;  // caustic irradiance on receivers, if any
};

}  // namespace prism

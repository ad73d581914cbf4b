#include "master/commands/RenderOptions.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace prism {

void applyOverrides(const RenderOptions& o, CameraDesc& camera) {
  if (o.cameraPosition) camera.position = *o.cameraPosition;
  if (o.lookAt) camera.lookAt = *o.lookAt;
  if ((o.cameraPosition || o.lookAt) && camera.position == camera.lookAt) {
    throw std::invalid_argument(
        "the camera's position and look-at point are the same point, so there is no view "
        "direction (--camera-position, --look-at)");
  }
}

Vec3 parseVec3(const std::string& text) {
  float v[3];
  const char* at = text.c_str();
  for (int i = 0; i < 3; ++i) {
    char* end = nullptr;
    v[i] = std::strtof(at, &end);
    const char expected = i < 2 ? ',' : '\0';
    if (end == at || *end != expected || !std::isfinite(v[i])) {
      throw std::invalid_argument("'" + text + "' is not three numbers X,Y,Z");
    }
    at = end + 1;
  }
  return {v[0], v[1], v[2]};
}

void applyOverrides(const RenderOptions& o, RenderSettings& s) {
  if (o.width) s.width = *o.width;
  if (o.height) s.height = *o.height;
  if (o.samples) s.samplesPerPixel = *o.samples;
  if (o.maxDepth) s.maxDepth = *o.maxDepth;
  if (o.seed) s.seed = *o.seed;
  if (o.exposure) s.exposure = *o.exposure;
  if (o.triangleTest) s.triangleTest = *o.triangleTest;
}

void applyOverrides(const RenderOptions& o, CausticSettings& c) {
  if (o.causticMethod) c.method = *o.causticMethod;
  if (o.photons) c.photons = *o.photons;
  if (o.gather) {
    c.gather = *o.gather;
    c.automaticGather = false;
  }
  if (o.gatherNoise) {
    c.gatherNoise = *o.gatherNoise;
    c.automaticGather = true;
  }
  if (o.passes) c.passes = *o.passes;
  if (o.progressive) c.progressive = *o.progressive;
  if (o.gatherRadius) c.maxRadius = c.radius = *o.gatherRadius;
  // A budget bounds progressive passes, so it asks for them (a classic render is one pass), and
  // without --passes it runs them until it ends (the scene's count, 16 by default, stopped a
  // 60 s budget at 22 s).
  if (o.timeBudget) {
    c.timeBudgetSeconds = *o.timeBudget;
    c.progressive = true;
    if (!o.passes) c.passes = kPassesUntilBudget;
  }
  if (o.mapResolution) c.mapResolution = *o.mapResolution;
  if (o.mapSteps) c.mapSteps = *o.mapSteps;
  if (o.mapBlurSigma) c.mapBlurSigma = *o.mapBlurSigma;
  if (o.mapBlurRadius) c.mapBlurRadius = *o.mapBlurRadius;
  if (o.mapPaths) c.mapPaths = *o.mapPaths;
  // Caustic-map parameters alone ask for caustic mapping.
  if ((o.mapResolution || o.mapSteps || o.mapBlurSigma || o.mapBlurRadius || o.mapPaths) &&
      !o.causticMethod && c.method == CausticMethod::None) {
    c.method = CausticMethod::CausticMap;
  }
  // Asking for passes, a budget or a photon image means asking for photon mapping.
  if ((o.progressive || o.passes || o.timeBudget || o.photons) && !o.causticMethod &&
      c.method == CausticMethod::None) {
    c.method = CausticMethod::PhotonMap;
  }
}

}  // namespace prism

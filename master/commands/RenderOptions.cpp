#include "master/commands/RenderOptions.h"

namespace prism {

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
  if (o.timeBudget) c.timeBudgetSeconds = *o.timeBudget;
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

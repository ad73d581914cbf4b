#include "caustics/CausticMapMemory.h"

#include <string>

#include "caustics/LightFrustum.h"

namespace prism {
namespace {

// Views over all lights: the frustums are cheap to make (no texel is allocated).
uint64_t viewCount(const Scene& scene, int resolution) {
  uint64_t views = 0;
  for (const PointLightDesc& light : scene.lights()) {
    views += LightFrustum(light.position, scene.causticCasters(), resolution).views().size();
  }
  return views;
}

}  // namespace

uint64_t causticMapBytes(uint64_t views, int resolution) {
  const uint64_t side = static_cast<uint64_t>(resolution > 0 ? resolution : 0);
  return saturatingMultiply(saturatingMultiply(views, saturatingMultiply(side, side)),
                            kCausticMapBytesPerTexel);
}

uint64_t causticMapBytes(const Scene& scene, int resolution) {
  return causticMapBytes(viewCount(scene, resolution), resolution);
}

std::optional<std::string> causticMapsRefusal(const Scene& scene, const MemoryLimit& limit) {
  const int resolution = scene.causticSettings().mapResolution;
  const uint64_t views = viewCount(scene, resolution);
  const uint64_t needed = causticMapBytes(views, resolution);
  if (needed <= limit.bytes) return std::nullopt;
  const size_t lights = scene.lights().size();
  return memoryRefusal("caustic maps of " + std::to_string(lights) +
                           (lights == 1 ? " light" : " lights") + " at " +
                           std::to_string(resolution) + " texels a side (" + std::to_string(views) +
                           (views == 1 ? " view" : " views") + ")",
                       needed, limit, "reduce --map-resolution");
}

void checkCausticMapsFit(const Scene& scene, const MemoryLimit& limit) {
  if (scene.causticSettings().method != CausticMethod::CausticMap) return;
  if (const std::optional<std::string> why = causticMapsRefusal(scene, limit)) {
    throw ResourceLimitError(*why);
  }
}

}  // namespace prism

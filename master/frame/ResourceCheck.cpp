#include "master/frame/ResourceCheck.h"

#include <string>

#include "caustics/CausticMapMemory.h"

namespace prism {
namespace {

std::string dimensions(const RenderSettings& s) {
  return std::to_string(s.width) + "x" + std::to_string(s.height);
}

void require(uint64_t needed, const MemoryLimit& limit, const std::string& what,
             const std::string& hint) {
  if (needed > limit.bytes) throw ResourceLimitError(memoryRefusal(what, needed, limit, hint));
}

}  // namespace

uint64_t frameMemoryBytes(const RenderSettings& s) {
  const uint64_t pixels = saturatingMultiply(static_cast<uint64_t>(std::max(s.width, 0)),
                                             static_cast<uint64_t>(std::max(s.height, 0)));
  return saturatingMultiply(pixels, 2 * sizeof(Color));  // frame buffer + tiles in flight
}

void checkRenderFits(const RenderSettings& s, const MemoryLimit& limit) {
  require(frameMemoryBytes(s), limit, "a " + dimensions(s) + " image's frame buffer",
          "reduce --width/--height");
}

uint64_t tileCount(const RenderSettings& s, int tileSize) {
  const uint64_t edge = tileSize > 0 ? static_cast<uint64_t>(tileSize) : 8;  // automatic: >= 8
  const uint64_t across = (static_cast<uint64_t>(std::max(s.width, 0)) + edge - 1) / edge;
  const uint64_t down = (static_cast<uint64_t>(std::max(s.height, 0)) + edge - 1) / edge;
  return saturatingMultiply(across, down);
}

uint64_t tileMemoryBytes(uint64_t tiles) {
  return saturatingMultiply(tiles, 64);
}

void checkTilesFit(const RenderSettings& s, int tileSize, const MemoryLimit& limit) {
  const uint64_t tiles = tileCount(s, tileSize);
  if (tiles > kMaxTileCount) {
    throw ResourceLimitError("a " + dimensions(s) + " image in " +
                             (tileSize > 0 ? std::to_string(tileSize) + "-pixel" : "automatic") +
                             " tiles makes " + std::to_string(tiles) + " tiles; at most " +
                             std::to_string(kMaxTileCount) + " are allowed (raise --tile-size)");
  }
  require(tileMemoryBytes(tiles), limit, std::to_string(tiles) + " tiles' bookkeeping",
          "raise --tile-size");
}

uint64_t photonMemoryBytes(const CausticSettings& c) {
  if (c.method != CausticMethod::PhotonMap) return 0;
  // 28-byte photons held three times (shares, map, outgoing message), a 4-byte tree index, about
  // one 8-byte node share, the tree's leaf-order position and photon index (16), and the
  // gather's disc (40) and radius (4) per photon.
  constexpr uint64_t kBytesPerPhoton = 3 * 28 + 4 + 8 + 16 + 40 + 4;
  return saturatingMultiply(c.photons, kBytesPerPhoton);
}

uint64_t causticMapMemoryBytes(const CausticSettings& c, size_t lights) {
  if (c.method != CausticMethod::CausticMap) return 0;
  return causticMapBytes(lights, c.mapResolution);  // one view a light: the fewest there can be
}

void checkCausticsFit(const CausticSettings& c, size_t lights, const MemoryLimit& limit) {
  require(photonMemoryBytes(c), limit, std::to_string(c.photons) + " photons per pass",
          "reduce --photons, or use more --passes of fewer");
  require(causticMapMemoryBytes(c, lights), limit,
          "caustic maps of " + std::to_string(lights) + (lights == 1 ? " light" : " lights") +
              " at " + std::to_string(c.mapResolution) +
              " texels a side (one view a light, at least)",
          "reduce --map-resolution");
}

void checkSceneFits(const SceneDescription& d, int tileSize, const MemoryLimit& limit) {
  checkGeometryFits(d, limit);
  const uint64_t geometry = geometryMemoryBytes(d);
  const uint64_t frame = frameMemoryBytes(d.render);
  const uint64_t tiles = tileMemoryBytes(tileCount(d.render, tileSize));
  const uint64_t caustics = saturatingAdd(photonMemoryBytes(d.caustics),
                                          causticMapMemoryBytes(d.caustics, d.lights.size()));
  const uint64_t total =
      saturatingAdd(saturatingAdd(geometry, frame), saturatingAdd(tiles, caustics));
  require(total, limit,
          "the run (geometry " + formatBytes(static_cast<double>(geometry)) + ", frame " +
              formatBytes(static_cast<double>(frame)) + ", caustics " +
              formatBytes(static_cast<double>(caustics)) + ")",
          "reduce what is largest");
}

}  // namespace prism

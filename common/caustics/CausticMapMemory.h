// What a scene's caustic maps hold in memory, known exactly once the scene is built: each light's
// frustum has one view, or six when its casters surround it. Checked against the run's memory
// limit before any map is built, on every rank.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "caustics/CausticMap.h"
#include "util/MemorySize.h"

namespace prism {

// A texel's receiver, caster and lookup records, and the build's flux and two blur buffers.
inline constexpr uint64_t kCausticMapBytesPerTexel =
    sizeof(ReceiverTexel) + sizeof(CasterTexel) + CausticMap::kLookupTexelBytes + 3 * sizeof(Color);

// Bytes `views` light views take at `resolution` texels a side.
uint64_t causticMapBytes(uint64_t views, int resolution);
// Bytes the maps of every light of the scene take at `resolution` texels a side.
uint64_t causticMapBytes(const Scene& scene, int resolution);

// Why the scene's caustic maps (at its map resolution, whatever its caustic method) cannot fit
// in limit: the bytes, the views and the limit; nothing when they fit. The viewer asks before
// the user switches to caustic maps.
std::optional<std::string> causticMapsRefusal(const Scene& scene, const MemoryLimit& limit);
// When the scene uses caustic mapping: throws ResourceLimitError with causticMapsRefusal's
// message if its maps cannot fit.
void checkCausticMapsFit(const Scene& scene, const MemoryLimit& limit);

}  // namespace prism

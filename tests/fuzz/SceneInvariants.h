// What every parsed scene must satisfy, whatever the input format: the master broadcasts the
// description and the slaves decode it, so anything a parser accepts must pass the wire
// decoder's checks (which reject what would crash the renderer).
#pragma once

#include "scene/SceneDescription.h"

namespace prism::fuzz {

// Throws InvariantBroken when scene would not survive the trip to the slaves.
void checkScene(const SceneDescription& scene);

// Throws InvariantBroken for indices past the positions, normals that do not match the positions,
// or non-finite vertex data.
void checkMesh(const MeshDesc& mesh);

}  // namespace prism::fuzz

// Entry point for reading a scene file of any supported format.
#pragma once

#include <string>

#include "scene/SceneDescription.h"
#include "util/MemorySize.h"

namespace prism {

// Reads the file at path, chooses the parser by extension (.yaml/.yml: Prism's YAML format,
// .nff: Eric Haines' Neutral File Format, .obj/.ply/.gltf/.glb: a model file as a scene,
// parse/ModelScene.h) and returns a validated description with every
// referenced mesh and image loaded. Throws SceneError ("file:line:col: message") on bad input.
// With a limit, a file whose reading could pass it is refused before it is read (its size
// times the parser's worst expansion, scene/MeshBudget.h), and so is every mesh it names.
SceneDescription loadScene(const std::string& path, const MemoryLimit& limit = {});

// Reads a whole file as text; throws SceneError naming the file when it cannot be read.
std::string readTextFile(const std::string& path, const FileLoc& referencedFrom = {});

}  // namespace prism

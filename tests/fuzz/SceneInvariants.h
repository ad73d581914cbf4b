// What every parsed scene must satisfy, whatever the input format: the master broadcasts the
// description and the slaves decode it, so anything a parser accepts must pass the wire
// decoder's checks (which reject what would crash the renderer).
#pragma once

#include "fuzz/Harnesses.h"
#include "scene/ModelDesc.h"
#include "scene/SceneDescription.h"
#include "util/FileLoc.h"

namespace prism::fuzz {

// Throws InvariantBroken when scene would not survive the trip to the slaves.
void checkScene(const SceneDescription& scene);

// Throws InvariantBroken for indices past the positions, normals that do not match the positions,
// or non-finite vertex data.
void checkMesh(const MeshDesc& mesh);

// Throws InvariantBroken for a model whose meshes break checkMesh, whose texture coordinates,
// colours or materials are not finite (or colours negative, or an ior below 1), or which placed
// into a scene (parse/ModelFile.h) would not survive the trip to the slaves.
void checkModel(const ModelDesc& model);

// A model loader's outcome on fuzz input: load() throwing SceneError is a clean rejection; an
// accepted model must pass checkModel and hold at least one triangle.
template <class Load>
Outcome modelOutcome(Load load) {
  ModelDesc model;
  try {
    model = load();
  } catch (const SceneError&) {
    return Outcome::Rejected;
  }
  checkModel(model);
  if (model.triangleCount() == 0) throw InvariantBroken("accepted a model without triangles");
  return Outcome::Accepted;
}

// A mesh parser's outcome on fuzz input: parse() throwing SceneError is a clean rejection; an
// accepted mesh must pass checkMesh and hold at least one triangle.
template <class Parse>
Outcome meshOutcome(Parse parse) {
  MeshDesc mesh;
  try {
    mesh = parse();
  } catch (const SceneError&) {
    return Outcome::Rejected;
  }
  checkMesh(mesh);
  if (mesh.indices.empty()) throw InvariantBroken("accepted a mesh without triangles");
  return Outcome::Accepted;
}

}  // namespace prism::fuzz

// A model file rendered as a scene without a scene file (`prism render model.glb`): its meshes,
// materials and textures, its own camera and lights where it has them, else a camera that frames
// its bounds and a light that shows its shape. The choices go into the description's notes.
#pragma once

#include "scene/ModelDesc.h"

namespace prism {

// The camera a model without one is seen through: looking at the centre of its bounds from the
// front (+Z), a little above and to the right, +Y up (the convention of OBJ and glTF), far
// enough that the bounding sphere fills the 45° field of view with a margin.
CameraDesc cameraFramingBounds(const Aabb& bounds);

// The light of a model without lights: a point light above and to the left of the camera,
// bright enough that a white surface facing it at the model's centre reflects about its
// albedo (inverse-square, radiance ≈ albedo · cos).
PointLightDesc lightForCamera(const CameraDesc& camera, const Aabb& bounds);

// The model as a scene, render settings at their defaults.
SceneDescription sceneOfModel(ModelDesc model);

}  // namespace prism

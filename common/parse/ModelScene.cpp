#include "parse/ModelScene.h"

#include <cmath>
#include <utility>

#include "math/Aabb.h"
#include "math/Ball.h"
#include "parse/ModelFile.h"

namespace prism {

namespace {

// The ambient radiance and background of a model shown on its own: dark enough to keep the
// shape's shading, light enough that a silhouette against the background shows.
constexpr float kModelBackground = 0.05f;

}  // namespace

CameraDesc cameraFramingBounds(const Aabb& bounds) {
  const Ball ball = ballAround(bounds);
  CameraDesc camera;
  const float radius = ball.radius > 0.0f ? ball.radius : 1.0f;
  const float halfAngle = 0.5f * glm::radians(camera.fovDegrees);
  const float distance = 1.1f * radius / std::sin(halfAngle);
  const Vec3 from = glm::normalize(Vec3(0.45f, 0.35f, 1.0f));
  camera.lookAt = ball.center;
  camera.position = ball.center + distance * from;
  camera.up = Vec3(0.0f, 1.0f, 0.0f);
  return camera;
}

PointLightDesc lightForCamera(const CameraDesc& camera, const Aabb& bounds) {
  const Vec3 forward = glm::normalize(camera.lookAt - camera.position);
  const Vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const Vec3 up = glm::cross(right, forward);
  const float distance = glm::length(camera.lookAt - camera.position);
  PointLightDesc light;
  light.position = camera.position + 0.5f * distance * (up - right);
  // Radiance of a white Lambertian surface facing it: (1/π) · I / d². I = π · d² gives 1.
  const float toCentre = glm::length(ballAround(bounds).center - light.position);
  light.intensity = Color(kPi * toCentre * toCentre);
  return light;
}

SceneDescription sceneOfModel(ModelDesc model) {
  SceneDescription scene;
  scene.sourcePath = model.source;
  scene.camera.loc = FileLoc{model.source};
  Aabb bounds;
  for (const MeshDesc& mesh : model.meshes) {
    for (const Vec3& p : mesh.positions) bounds.extend(p);
  }
  const bool ownCamera = model.camera.has_value(), ownLights = !model.lights.empty();
  const std::string source = model.source;
  ModelPlacement placement;
  placement.takeCamera = ownCamera;
  placement.takeLights = ownLights;
  placeModel(std::move(model), placement, scene);
  if (!ownCamera) scene.camera = cameraFramingBounds(bounds);
  scene.camera.loc = FileLoc{source};
  if (!ownLights) {
    scene.lights.push_back(lightForCamera(scene.camera, bounds));
    scene.lights.back().loc = FileLoc{source};
  }
  scene.background = Color(kModelBackground);
  scene.notes.push_back(ownCamera ? "camera: the file's own"
                                  : "camera: none in the file, so one framing the model's bounds");
  scene.notes.push_back(ownLights
                            ? "lights: the file's own (" + std::to_string(scene.lights.size()) + ")"
                            : "lights: none in the file, so one above the camera");
  return scene;
}

}  // namespace prism

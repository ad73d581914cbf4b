// Camera moves for the viewer, on a CameraDesc: walking (W/A/S/D, Q/E), turning in place
// (arrows), orbiting the look-at point (mouse drag) and zooming toward it (wheel). Steps scale
// with the distance to the look-at point, so a move feels the same in any scene. No Qt.
#pragma once

#include "scene/SceneDescription.h"

namespace prism {

class CameraController {
 public:
  explicit CameraController(const CameraDesc& home) : home_(home), camera_(home) {}

  const CameraDesc& camera() const { return camera_; }
  void reset() { camera_ = home_; }
  // Where the viewer resumes a view that moved from home.
  void setCamera(const CameraDesc& camera) { camera_ = camera; }

  // Moves position and look-at together, in steps of moveFraction × distance: along the view
  // direction (forward), the image's right vector, and the camera's up vector.
  void move(float forward, float right, float up);
  // Turns the view direction in place: yaw about the up vector, pitch about the right vector.
  void rotate(float yawDegrees, float pitchDegrees);
  // Orbits the position around the look-at point (yaw about up, pitch about right).
  void orbit(float yawDegrees, float pitchDegrees);
  // Moves toward the look-at point by the factor (< 1: closer), never closer than 1e-3 of the
  // starting distance.
  void zoom(float factor);

  float distance() const;
  static constexpr float kMoveFraction = 0.05f;

 private:
  CameraDesc home_;
  CameraDesc camera_;
};

}  // namespace prism

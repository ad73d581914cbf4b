#include "gui/CameraController.h"

#include <glm/gtc/matrix_transform.hpp>

namespace prism {
namespace {

Vec3 rotateAbout(const Vec3& v, const Vec3& axis, float degrees) {
  const glm::mat4 m = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::normalize(axis));
  return Vec3(m * glm::vec4(v, 0.0f));
}

// Stops a pitch short of the up vector, where the camera basis would degenerate.
bool tooSteep(const Vec3& direction, const Vec3& up) {
  return std::abs(glm::dot(glm::normalize(direction), glm::normalize(up))) > 0.995f;
}

}  // namespace

float CameraController::distance() const {
  return glm::length(camera_.lookAt - camera_.position);
}

void CameraController::move(float forward, float right, float up) {
  const Vec3 f = glm::normalize(camera_.lookAt - camera_.position);
  const Vec3 r = glm::normalize(glm::cross(f, camera_.up));
  const Vec3 u = glm::normalize(camera_.up);
  const Vec3 step = kMoveFraction * glm::length(home_.lookAt - home_.position) *
                    (forward * f + right * r + up * u);
  camera_.position += step;
  camera_.lookAt += step;
}

void CameraController::rotate(float yawDegrees, float pitchDegrees) {
  Vec3 d = camera_.lookAt - camera_.position;
  const Vec3 r = glm::normalize(glm::cross(d, camera_.up));
  d = rotateAbout(d, camera_.up, yawDegrees);
  const Vec3 pitched = rotateAbout(d, r, pitchDegrees);
  if (!tooSteep(pitched, camera_.up)) d = pitched;
  camera_.lookAt = camera_.position + d;
}

void CameraController::orbit(float yawDegrees, float pitchDegrees) {
  Vec3 d = camera_.position - camera_.lookAt;
  const Vec3 r = glm::normalize(glm::cross(camera_.lookAt - camera_.position, camera_.up));
  d = rotateAbout(d, camera_.up, yawDegrees);
  const Vec3 pitched = rotateAbout(d, r, pitchDegrees);
  if (!tooSteep(pitched, camera_.up)) d = pitched;
  camera_.position = camera_.lookAt + d;
}

void CameraController::zoom(float factor) {
  const Vec3 d = camera_.position - camera_.lookAt;
  const float minimum = 1e-3f * glm::length(home_.position - home_.lookAt);
  const float length = std::max(glm::length(d) * factor, minimum);
  camera_.position = camera_.lookAt + glm::normalize(d) * length;
}

}  // namespace prism

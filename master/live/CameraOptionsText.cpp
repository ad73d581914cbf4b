#include "master/live/CameraOptionsText.h"

#include <cstdio>

namespace prism {

std::string cameraOptionsText(const CameraDesc& camera) {
  char text[160];
  const Vec3& p = camera.position;
  const Vec3& l = camera.lookAt;
  std::snprintf(text, sizeof text, "--camera-position %.9g,%.9g,%.9g --look-at %.9g,%.9g,%.9g", p.x,
                p.y, p.z, l.x, l.y, l.z);
  return text;
}

}  // namespace prism

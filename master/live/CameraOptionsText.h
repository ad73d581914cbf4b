// The command-line options that render a camera's view, as the viewer prints them for the view
// it saved (Cli.cpp reads them back with parseVec3).
#pragma once

#include <string>

#include "scene/SceneDescription.h"

namespace prism {

// "--camera-position X,Y,Z --look-at X,Y,Z", each number printed so that it reads back as the
// same float.
std::string cameraOptionsText(const CameraDesc& camera);

}  // namespace prism

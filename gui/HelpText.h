// The keys the viewer understands, shown by the help overlay (h, F1) and in docs/viewer.md.
#pragma once

namespace prism {

inline constexpr const char* kViewerHelpText =
    "Prism viewer: keys\n"
    "\n"
    "  W / S        move forward / back\n"
    "  A / D        move left / right\n"
    "  Q / E        move down / up\n"
    "  arrows       turn (yaw, pitch)\n"
    "  mouse drag   orbit around the look-at point\n"
    "  wheel        zoom toward / away from it\n"
    "  r            reset the camera\n"
    "  N            normals debug view\n"
    "  R            caustic map: caster positions (light space)\n"
    "  P            caustic map: receiver positions (light space)\n"
    "  C            caustic map: irradiance (light space)\n"
    "  b            caustic map: Gaussian blur on / off\n"
    "  n            back to the image\n"
    "  t            show / hide tiles in flight\n"
    "  + / -        samples per pixel per pass up / down\n"
    "  h, F1        this help\n"
    "  q            quit  (Esc closes this help)\n"
    "\n"
    "Tiles in flight are outlined in the colour of the rank rendering them.\n"
    "While the camera is still, full-resolution passes are averaged.\n";

}  // namespace prism

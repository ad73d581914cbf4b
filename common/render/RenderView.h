// What to render when it is not the scene file's own camera and settings: the viewer's camera,
// a reduced preview resolution, the samples and seed of one refinement pass, a debug view.
// `prism render` never uses this; its TileRenderer reads the Scene's camera and settings.
#pragma once

#include <cstdint>

#include "scene/SceneDescription.h"

namespace prism {

// What a pixel shows. A new per-pixel view gets its enumerator here, its shading in
// render/DebugShading.cpp and its case in isKnown in wire/WireEnums.h. The caustic maps' debug
// views are not per pixel: the viewer shows them in light space (gui/LightSpaceImage.h).
enum class DebugView : uint8_t {
  Image = 0,    // radiance, as `prism render` computes it
  Normals = 1,  // shading normal of the first hit, mapped from [-1, 1] to [0, 1]
};

struct RenderView {
  CameraDesc camera;
  int width = 0;  // the image the tiles belong to (a preview is smaller than the final image)
  int height = 0;
  int samplesPerPixel = 1;
  uint64_t seed = 0;  // each refinement pass uses its own, so passes average to more samples
  DebugView debugView = DebugView::Image;
  bool causticMapBlur = true;  // caustic mapping: the scene's Gaussian blur, or none (viewer `b`)
  // One sample per pixel through a jittered point instead of the centre: the viewer's passes
  // after the first, which must differ from it to average to more samples.
  bool jitterSingleSample = false;
  // > 0: the frame is only shown until the next replaces it, never averaged (a moving camera's
  // frame), so tiles rendered on other ranks travel as the 8-bit display bytes this exposure
  // gives (3 bytes a pixel, not 12; wire::TileResultMessage): what the window shows is the same.
  float displayExposure = 0.0f;
};

}  // namespace prism

// The scenes where caustic mapping is put to the test against photon mapping, and the receiver
// rectangles its caustics are scored on (docs/caustics.md, "Where caustic mapping fails").
// Shared by tests/common/caustics/CausticMapFailures_test.cpp and
// tests/bench/caustic_map_study.cpp.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "parse/SceneLoader.h"
#include "tests/common/caustics/BallOverFloorScene.h"
#include "tests/common/caustics/CausticFluxGrid.h"

namespace prism::test {

struct ScoredRegion {
  std::string name;
  FluxGrid grid;
};

struct CausticCase {
  std::string name;
  SceneDescription scene;
  std::vector<ScoredRegion> regions;
};

inline SceneDescription loadSeedScene(const std::string& file) {
  SceneDescription d = loadScene(std::string(PRISM_SOURCE_DIR) + "/scenes/" + file);
  d.caustics.method = CausticMethod::CausticMap;
  return d;
}

// scenes/caustic-glass-sphere.yaml: the ball's shadow and focus on the floor.
inline CausticCase glassSphereCase() {
  return {"glass sphere",
          loadSeedScene("caustic-glass-sphere.yaml"),
          {{"floor", horizontalGrid(0.0f, -1.5f, 1.5f, -1.5f, 1.5f, 0.05f)}}};
}

// scenes/caustic-map-hidden-receiver.yaml: the floor under the card (hidden from the light),
// the card's top, and the open floor beside it.
inline CausticCase hiddenReceiverCase() {
  return {"hidden receiver",
          loadSeedScene("caustic-map-hidden-receiver.yaml"),
          {{"floor under the card", horizontalGrid(0.0f, 0.05f, 1.55f, -1.5f, 1.5f, 0.05f)},
           {"card top", horizontalGrid(1.6f, 0.05f, 1.55f, -1.5f, 1.5f, 0.05f)},
           {"open floor", horizontalGrid(0.0f, -1.55f, -0.05f, -1.5f, 1.5f, 0.05f)}}};
}

// A glass ball (n = 1.5, radius 1, centre 1.2 above the floor) lit from 8 away at `elevation`
// degrees above the horizon: the lower the light, the more the floor's receiver texels are
// stretched along it (area Ω·d²/cos θ) and the longer the caustic. Scored on a rectangle around
// the ball's shadow, 60 × 60 cells.
inline CausticCase grazingCase(float elevationDegrees) {
  const float e = elevationDegrees * 3.14159265f / 180.0f;
  const Vec3 centre{0.0f, 1.2f, 0.0f};
  SceneDescription d = ballOverFloorScene(1.5f);  // the shared ball, moved and relit
  d.spheres.at(0).center = centre;
  d.materials.at(1).diffuse = Color(0.75f);
  d.lights.at(0).position = centre + 8.0f * Vec3(-std::cos(e), std::sin(e), 0.0f);
  d.lights.at(0).intensity = Color(150.0f);
  d.caustics.method = CausticMethod::CausticMap;
  // The shadow's centre, and its half-length along x (the ball's radius over sin e, plus room).
  const float middle = centre.y / std::tan(e), half = 1.6f / std::sin(e);
  FluxGrid g = horizontalGrid(0.0f, middle - half, middle + half, -1.6f, 1.6f, 1.0f);
  g.cellsU = g.cellsV = 60;
  return {
      "grazing " + std::to_string(static_cast<int>(elevationDegrees)) + " deg", d, {{"floor", g}}};
}

}  // namespace prism::test

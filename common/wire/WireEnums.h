// The enumerations that cross the wire, each a u32 there: which values are enumerators (any other
// value would fall through every switch in the renderer) and what an error calls the field.
// No default cases: -Wswitch points here when an enumerator is added, so the decoder learns it.
#pragma once

#include "caustics/PhotonGatherSettings.h"
#include "render/RenderView.h"
#include "scene/SceneDescription.h"

namespace prism::wire {

inline bool isKnown(Projection p) {
  switch (p) {
    case Projection::Perspective:
    case Projection::Orthographic:
      return true;
  }
  return false;
}

inline bool isKnown(TriangleTest t) {
  switch (t) {
    case TriangleTest::MollerTrumbore:
    case TriangleTest::PlaneThenInside:
    case TriangleTest::Watertight:
      return true;
  }
  return false;
}

inline bool isKnown(InstructionSet isa) {
  switch (isa) {
    case InstructionSet::Auto:
    case InstructionSet::Baseline:
    case InstructionSet::V2:
    case InstructionSet::V3:
    case InstructionSet::V4:
      return true;
  }
  return false;
}

inline bool isKnown(CausticMethod m) {
  return static_cast<size_t>(m) < kCausticMethodCount;  // scene/CausticMethods.h numbers them
}

inline bool isKnown(CausticMapPaths p) {
  switch (p) {
    case CausticMapPaths::FrontFace:
    case CausticMapPaths::Traced:
      return true;
  }
  return false;
}

inline bool isKnown(PhotonFilter f) {
  switch (f) {
    case PhotonFilter::Box:
    case PhotonFilter::Cone:
    case PhotonFilter::Epanechnikov:
      return true;
  }
  return false;
}

inline bool isKnown(CausticRole role) {
  switch (role) {
    case CausticRole::Auto:
    case CausticRole::Cast:
    case CausticRole::Receive:
    case CausticRole::Both:
    case CausticRole::Off:
      return true;
  }
  return false;
}

inline bool isKnown(DebugView view) {
  switch (view) {
    case DebugView::Image:
    case DebugView::Normals:
      return true;
  }
  return false;
}

// "invalid caustic role 256 at offset 40"
inline const char* enumName(Projection) {
  return "camera projection";
}
inline const char* enumName(TriangleTest) {
  return "triangle test";
}
inline const char* enumName(InstructionSet) {
  return "instruction set";
}
inline const char* enumName(CausticMethod) {
  return "caustic method";
}
inline const char* enumName(CausticMapPaths) {
  return "caustic map paths";
}
inline const char* enumName(PhotonFilter) {
  return "photon filter";
}
inline const char* enumName(CausticRole) {
  return "caustic role";
}
inline const char* enumName(DebugView) {
  return "debug view";
}

}  // namespace prism::wire

// Every caustic method, listed once (docs/caustics.md describes them). From this list follow the
// enumeration, the names the scene file's `caustics.method` and `--caustics` read
// (scene/SettingNames.h), the wire's check of a decoded method (wire/WireEnums.h) and the
// viewer's switch with its labels (gui/MainWindow.cpp). What a method computes is its own:
// docs/README.md, "Adding a caustic method", lists where.
//
// X(Method, name, title, description): the enumerator, the name in scene files and on the
// command line, the title the viewer and the summary show, and the viewer's tooltip.
#pragma once

#include <cstddef>

#define PRISM_CAUSTIC_METHODS(X)                                                               \
  X(None, "none", "none", "Direct light only")                                                 \
  X(PhotonMap, "photon_map", "photon map (progressive)",                                       \
    "Every full pass traces its own photons and gathers them with a shrinking radius; the "    \
    "averaged passes are progressive photon mapping")                                          \
  X(CausticMap, "caustic_map", "caustic map",                                                  \
    "Light-space caustic maps (Shah et al. 2007), built once per blur setting on every rank; " \
    "the preview shows them too")

namespace prism {

#define PRISM_CAUSTIC_ENUMERATOR(Method, name, title, description) Method,
enum class CausticMethod { PRISM_CAUSTIC_METHODS(PRISM_CAUSTIC_ENUMERATOR) };
#undef PRISM_CAUSTIC_ENUMERATOR

#define PRISM_CAUSTIC_ONE(Method, name, title, description) +1
inline constexpr size_t kCausticMethodCount = 0 PRISM_CAUSTIC_METHODS(PRISM_CAUSTIC_ONE);
#undef PRISM_CAUSTIC_ONE

struct CausticMethodInfo {
  CausticMethod method;
  const char* name;
  const char* title;
  const char* description;
};

#define PRISM_CAUSTIC_INFO(Method, name, title, description) \
  {CausticMethod::Method, name, title, description},
inline constexpr CausticMethodInfo kCausticMethods[] = {PRISM_CAUSTIC_METHODS(PRISM_CAUSTIC_INFO)};
#undef PRISM_CAUSTIC_INFO

// The method's entry; methods are numbered in the list's order.
constexpr const CausticMethodInfo& causticMethodInfo(CausticMethod method) {
  return kCausticMethods[static_cast<size_t>(method)];
}

}  // namespace prism

// The names of every enumerated setting, one table per enum, shared by the scene parsers and the
// command line so a value copied from a scene file works as an option and back. Names match
// ignoring case and with '-' and '_' alike ("photon-map" is "photon_map"); errors and help print
// the canonical names, spelt as in scene files.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "scene/SceneDescription.h"

namespace prism {

template <typename E>
struct NamedValue {
  std::string_view name;
  E value;
};

// "Photon-Map" -> "photon_map": the form names are compared in.
std::string normalisedName(std::string_view text);

template <typename E>
struct NameTable {
  std::span<const NamedValue<E>> names;         // canonical, in the order help lists them
  std::span<const NamedValue<E>> aliases = {};  // also accepted, never listed

  std::optional<E> find(std::string_view text) const {
    const std::string wanted = normalisedName(text);
    for (const auto& table : {names, aliases}) {
      for (const NamedValue<E>& n : table) {
        if (n.name == wanted) return n.value;
      }
    }
    return std::nullopt;
  }

  std::string_view nameOf(E value) const {
    for (const NamedValue<E>& n : names) {
      if (n.value == value) return n.name;
    }
    return "?";
  }

  // "none, photon_map or caustic_map" (last = " or "), or "none|photon_map|caustic_map".
  std::string list(std::string_view separator = ", ", std::string_view last = " or ") const {
    std::string out;
    for (size_t i = 0; i < names.size(); ++i) {
      if (i > 0) out += i + 1 == names.size() ? last : separator;
      out += names[i].name;
    }
    return out;
  }
};

inline constexpr NamedValue<Projection> kProjectionList[] = {
    {"perspective", Projection::Perspective}, {"orthographic", Projection::Orthographic}};
inline constexpr NameTable<Projection> kProjectionNames{kProjectionList};

inline constexpr NamedValue<TriangleTest> kTriangleTestList[] = {
    {"moller_trumbore", TriangleTest::MollerTrumbore},
    {"plane_inside", TriangleTest::PlaneThenInside},
    {"watertight", TriangleTest::Watertight}};
inline constexpr NameTable<TriangleTest> kTriangleTestNames{kTriangleTestList};

#define PRISM_CAUSTIC_NAME(Method, name, title, description) {name, CausticMethod::Method},
inline constexpr NamedValue<CausticMethod> kCausticMethodList[] = {
    PRISM_CAUSTIC_METHODS(PRISM_CAUSTIC_NAME)};
#undef PRISM_CAUSTIC_NAME
// "map" is the short name users write for caustic mapping.
inline constexpr NamedValue<CausticMethod> kCausticMethodAliases[] = {
    {"map", CausticMethod::CausticMap}};
inline constexpr NameTable<CausticMethod> kCausticMethodNames{kCausticMethodList,
                                                              kCausticMethodAliases};

inline constexpr NamedValue<CausticMapPaths> kCausticMapPathsList[] = {
    {"front_face", CausticMapPaths::FrontFace}, {"traced", CausticMapPaths::Traced}};
inline constexpr NameTable<CausticMapPaths> kCausticMapPathsNames{kCausticMapPathsList};

inline constexpr NamedValue<PhotonFilter> kPhotonFilterList[] = {
    {"box", PhotonFilter::Box},
    {"cone", PhotonFilter::Cone},
    {"epanechnikov", PhotonFilter::Epanechnikov}};
inline constexpr NameTable<PhotonFilter> kPhotonFilterNames{kPhotonFilterList};

inline constexpr NamedValue<CausticRole> kCausticRoleList[] = {{"auto", CausticRole::Auto},
                                                               {"cast", CausticRole::Cast},
                                                               {"receive", CausticRole::Receive},
                                                               {"both", CausticRole::Both},
                                                               {"off", CausticRole::Off}};
inline constexpr NameTable<CausticRole> kCausticRoleNames{kCausticRoleList};

}  // namespace prism

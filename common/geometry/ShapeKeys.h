// The keys a primitive is written with in a scene file, declared beside the primitive so that
// one reader (parse/YamlSceneObjects.cpp) reads every kind in geometry/ShapeKinds.h the same way
// and the reference (docs/scene-format.md) can be checked against them. Every kind also takes
// 'material' and 'caustic', which the reader adds.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "math/Vec.h"

namespace prism {

// How a key's value is read and checked.
enum class KeyValue {
  Point,        // three numbers
  Direction,    // three numbers, not all zero; stored normalised
  Positive,     // a number above 0
  NonNegative,  // a number of at least 0
};

template <class Desc>
struct ShapeKey {
  std::string_view name;
  KeyValue value = KeyValue::Point;
  Vec3 Desc::*vector = nullptr;   // where a Point or Direction goes
  float Desc::*number = nullptr;  // where a Positive or NonNegative goes
  bool required = true;           // else the description's default stays

  static constexpr ShapeKey point(std::string_view name, Vec3 Desc::*member) {
    return {name, KeyValue::Point, member, nullptr, true};
  }
  static constexpr ShapeKey direction(std::string_view name, Vec3 Desc::*member) {
    return {name, KeyValue::Direction, member, nullptr, true};
  }
  static constexpr ShapeKey positive(std::string_view name, float Desc::*member) {
    return {name, KeyValue::Positive, nullptr, member, true};
  }
  static constexpr ShapeKey nonNegative(std::string_view name, float Desc::*member,
                                        bool required = true) {
    return {name, KeyValue::NonNegative, nullptr, member, required};
  }
};

// What is wrong with a description whose keys were each fine alone (a cone whose base is its
// apex): the key the reader points at, and the message.
struct ShapeProblem {
  std::string_view key;
  std::string message;
};

// What the keys' kinds require of the values (a positive radius, a direction that is not the
// zero vector), then the description's own problem(): the reader checks each key as it reads
// it, and a description from elsewhere (the wire) is checked with this.
template <class Desc>
std::optional<ShapeProblem> shapeProblem(const Desc& d) {
  for (const ShapeKey<Desc>& key : Desc::keys()) {
    const std::string name = "'" + std::string(key.name) + "'";
    switch (key.value) {
      case KeyValue::Point:
        if (!isFinite(d.*key.vector)) return ShapeProblem{key.name, name + " must be finite"};
        break;
      case KeyValue::Direction:
        if (!isFinite(d.*key.vector) || d.*key.vector == Vec3(0.0f)) {
          return ShapeProblem{key.name, name + " must be a finite vector other than zero"};
        }
        break;
      case KeyValue::Positive:
        if (!(d.*key.number > 0.0f) || !std::isfinite(d.*key.number)) {
          return ShapeProblem{key.name, name + " must be a finite number above 0"};
        }
        break;
      case KeyValue::NonNegative:
        if (!(d.*key.number >= 0.0f) || !std::isfinite(d.*key.number)) {
          return ShapeProblem{key.name, name + " must be a finite number of at least 0"};
        }
        break;
    }
  }
  return d.problem();
}

}  // namespace prism

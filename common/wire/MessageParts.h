// The field lists of the structs that messages carry but other layers own (render/, caustics/),
// and the checks that fields of messages use (wire/Fields.h says how a list reads).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "caustics/Photon.h"
#include "caustics/PhotonGatherSettings.h"
#include "caustics/PhotonTraceStats.h"
#include "render/RenderView.h"
#include "render/Tile.h"
#include "wire/ByteBuffer.h"
#include "wire/Fields.h"
#include "wire/SceneCodec.h"

namespace prism::wire {

template <>
struct Fields<TileRect> {
  PRISM_WIRE_FIELDS(x, y, width, height)
  // Non-empty, in the first quadrant, with a pixel count and far corner that fit in an int
  // (TileRect does its arithmetic in int).
  static void check(const TileRect& rect);
};

template <>
struct Fields<RayCounters> {
  PRISM_WIRE_FIELDS(primary, shadow, secondary, nonFinite)
};

template <>
struct Fields<PhotonTraceStats> {
  PRISM_WIRE_FIELDS(emitted, stored, missed, absorbed)
};

template <>
struct Fields<PhotonGatherSettings> {
  PRISM_WIRE_FIELDS(fixedRadius, k, radius, filter, radiusScale, automaticK)
  // k > 0, radius and radius scale positive and finite.
  static void check(const PhotonGatherSettings& gather);
};

// Position, power, direction: 28 bytes, the photon's memory, so a map of millions is copied in
// one go (11.6 MB: 33-50 ms number by number).
template <>
struct Fields<Photon> {
  PRISM_WIRE_FIELDS(position, power, direction)
  static constexpr bool kMemoryIsWireForm =
      sizeof(Photon) == 2 * sizeof(Vec3) + 2 * sizeof(uint16_t);
};

template <>
struct Fields<RenderView> {
  static void fields(auto& self, auto&& visit) {
    auto& [camera, width, height, samplesPerPixel, seed, debugView, causticMapBlur,
           jitterSingleSample, displayExposure] = self;
    visit(camera, width, height, samplesPerPixel, seed, debugView,
          flag(causticMapBlur, "caustic-map blur flag"), flag(jitterSingleSample, "jitter flag"),
          displayExposure);
  }
  // A positive size whose pixel count fits in an int, samples per pixel > 0, and a display
  // exposure that is 0 or gives invertible display bytes.
  static void check(const RenderView& view);
};

[[noreturn]] void throwBadPhoton(size_t index);
[[noreturn]] void throwBadRadius(size_t index);

// A photon the gather can use: finite position, power finite and not negative.
struct CheckPhoton {
  void operator()(const Photon& p, size_t index) const {
    if (!isFinite(p.position) || !isFinite(p.power) || p.power.x < 0.0f || p.power.y < 0.0f ||
        p.power.z < 0.0f) {
      throwBadPhoton(index);
    }
  }
};

// Gather radii: finite and not negative (a photon without k neighbours has its cap).
struct CheckRadius {
  void operator()(float radius, size_t index) const {
    if (!(radius >= 0.0f) || !std::isfinite(radius)) throwBadRadius(index);
  }
};

// A tile's pixels and the exposure before them: with exposure 0 as radiance (12 bytes a pixel);
// with exposure > 0 as the 8-bit display bytes that exposure gives (3 bytes a pixel), which
// arrive as the smallest radiance that gives each byte (image/DisplayBytes.h). Reading checks
// the exposure and that the pixels fill the tile's rectangle.
template <class Result, class Exposure>
struct TilePixels {
  Result& result;  // TileResult, const or not
  Exposure& exposure;

  void write(ByteWriter& w) const;
  void read(ByteReader& r);
  // What it carries, for tools that walk the fields (tests/fuzz/WireExamples.h).
  static void fields(auto& self, auto&& visit) { visit(self.exposure, self.result.pixels); }
};
template <class Result, class Exposure>
TilePixels<Result, Exposure> tilePixels(Result& result, Exposure& exposure) {
  return {result, exposure};
}

void writeTilePixels(ByteWriter& w, const TileResult& result, float exposure);
void readTilePixels(ByteReader& r, TileResult& result, float& exposure);

template <class Result, class Exposure>
void TilePixels<Result, Exposure>::write(ByteWriter& w) const {
  writeTilePixels(w, result, exposure);
}

template <class Result, class Exposure>
void TilePixels<Result, Exposure>::read(ByteReader& r) {
  readTilePixels(r, result, exposure);
}

}  // namespace prism::wire

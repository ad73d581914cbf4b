#include "scene/CubeMap.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "image/MipPyramid.h"
#include "image/SrgbImage.h"
#include "math/FloorToInt.h"
#include "math/Simd.h"
#include "util/Parallel.h"

namespace prism {

namespace {

// Where a direction meets the cube, before scaling to texels: the face and the face's
// coordinates sc, tc over the major axis ma (OpenGL 4.6 spec, table 8.19).
struct CubePoint {
  int face;
  float sc, tc, ma;
  // Across the face in [0, 1], t growing downwards in the image.
  float u() const { return 0.5f * (sc / ma + 1.0f); }
  float v() const { return 0.5f * (tc / ma + 1.0f); }
};

// The same table as axes: sc = signS·d[s], tc = signT·d[t], ma = signM·d[m].
struct FaceAxes {
  int s, t, m;
  float signS, signT, signM;
};
constexpr FaceAxes kFaceAxes[6] = {
    {2, 1, 0, -1.0f, -1.0f, 1.0f},  // +X
    {2, 1, 0, 1.0f, -1.0f, -1.0f},  // -X
    {0, 2, 1, 1.0f, 1.0f, 1.0f},    // +Y
    {0, 2, 1, 1.0f, -1.0f, -1.0f},  // -Y
    {0, 1, 2, 1.0f, -1.0f, 1.0f},   // +Z
    {0, 1, 2, -1.0f, -1.0f, -1.0f}  // -Z
};

// Inlined into the lookups (a call there cost 0.4 % of the default frame).
[[gnu::always_inline]] inline bool findCubePoint(const Vec3& d, CubePoint& point) {
  // The major axis picks the face; a zero major axis fails.
  const Vec3 a = absComponents(d);  // only compared
  if (a.x >= a.y && a.x >= a.z) {
    point = {d.x > 0.0f ? 0 : 1, d.x > 0.0f ? -d.z : d.z, -d.y, a.x};
  } else if (a.y >= a.z) {
    point = {d.y > 0.0f ? 2 : 3, d.x, d.y > 0.0f ? d.z : -d.z, a.y};
  } else {
    point = {d.z > 0.0f ? 4 : 5, d.z > 0.0f ? d.x : -d.x, -d.y, a.z};
  }
  return point.ma > 0.0f;
}

}  // namespace

namespace {

// Levels of faces (each level holds six of one kind) as their pyramids came out, moved in
// place. Faces of unequal sizes (the parser refuses them; a description built in code may not)
// repeat their 1x1 level at the top.
template <class Texels>
std::vector<std::array<Texels, 6>> levelsOf(std::array<std::vector<Texels>, 6>& pyramids) {
  size_t count = 0;
  for (const auto& pyramid : pyramids) count = std::max(count, pyramid.size());
  std::vector<std::array<Texels, 6>> levels(count);
  for (int f = 0; f < 6; ++f) {
    const size_t own = pyramids[f].size();
    for (size_t level = 0; level < count; ++level) {
      levels[level][f] = level < own ? std::move(pyramids[f][level]) : levels[own - 1][f];
    }
  }
  return levels;
}

// A texel as four lanes: its three channels and one more, unused. Floats read the next texel's
// first channel (blend() never reads a face's last texel this way); packed bytes go through the
// sRGB table.
inline simd::Float4 texelLanes(const ImageRgb& image, size_t index) {
  return simd::load<simd::Float4>(&image.pixels[index].x);
}
inline simd::Float4 texelLanes(const SrgbTexels& image, size_t index) {
  const std::array<float, 256>& linear = linearOfSrgbByte();
  const uint32_t texel = image.texels[index];
  return simd::Float4{linear[texel & 0xff], linear[(texel >> 8) & 0xff],
                      linear[(texel >> 16) & 0xff], 0.0f};
}

// Texel (x, y) of a face at a level; x or y one past the face's edge (-1 or size) reads the
// nearest texel of the neighbouring face the direction through it meets.
template <class Texels>
Color texel(const std::vector<std::array<Texels, 6>>& levels, int level, int face, int x, int y) {
  const Texels& image = levels[level][face];
  const bool inX = x >= 0 && x < image.width, inY = y >= 0 && y < image.height;
  if (inX && inY) return image.at(x, y);
  if (!inX && !inY) {
    // Past a corner of the cube no one face lies there: the mean of the three texels about the
    // corner (this face's and the two neighbours'), as OpenGL recommends, the same seen from
    // each of the three faces.
    const int cx = std::clamp(x, 0, image.width - 1), cy = std::clamp(y, 0, image.height - 1);
    return (image.at(cx, cy) + texel(levels, level, face, x, cy) +
            texel(levels, level, face, cx, y)) /
           3.0f;
  }
  // Past an edge: the direction through the texel's centre, on the face's plane extended, meets
  // the neighbouring face; its nearest texel there (the neighbour's row or column along the edge).
  const FaceAxes& axes = kFaceAxes[face];
  Vec3 d(0.0f);
  d[axes.s] = axes.signS * (2.0f * (static_cast<float>(x) + 0.5f) / image.width - 1.0f);
  d[axes.t] = axes.signT * (2.0f * (static_cast<float>(y) + 0.5f) / image.height - 1.0f);
  d[axes.m] = axes.signM;
  CubePoint p;
  findCubePoint(d, p);
  const Texels& next = levels[level][p.face];
  const int nx = std::clamp(floorToInt<int>(p.u() * next.width), 0, next.width - 1);
  const int ny = std::clamp(floorToInt<int>(p.v() * next.height), 0, next.height - 1);
  return next.at(nx, ny);
}

// Bilinearly filtered radiance of one level at u, v across the face; inlined into the lookups.
template <class Texels>
[[gnu::always_inline]] inline Color blend(const std::vector<std::array<Texels, 6>>& levels,
                                          int level, int face, float u, float v) {
  const Texels& image = levels[level][face];
  const float s = u * static_cast<float>(image.width) - 0.5f;
  const float t = v * static_cast<float>(image.height) - 0.5f;
  const int x0 = floorToInt<int>(s);
  const int y0 = floorToInt<int>(t);
  const float fx = s - static_cast<float>(x0);
  const float fy = t - static_cast<float>(y0);
  // Inside the face (nearly every lookup) the four texels need no neighbour, and each is read
  // as four lanes, so the three blends of glm::mix, a·(1 − f) + b·f, take one vector operation
  // per step instead of three: the same roundings channel by channel.
  const int w = image.width, h = image.height;
  if (x0 >= 0 && y0 >= 0 && x0 + 1 < w && y0 + 1 < h && !(x0 + 2 == w && y0 + 2 == h)) {
    const size_t i = static_cast<size_t>(y0) * w + x0;
    const simd::Float4 top = texelLanes(image, i) * (1.0f - fx) + texelLanes(image, i + 1) * fx;
    const simd::Float4 bottom =
        texelLanes(image, i + w) * (1.0f - fx) + texelLanes(image, i + w + 1) * fx;
    const simd::Float4 mixed = top * (1.0f - fy) + bottom * fy;
    return Color(mixed[0], mixed[1], mixed[2]);
  }
  const Color top =
      glm::mix(texel(levels, level, face, x0, y0), texel(levels, level, face, x0 + 1, y0), fx);
  const Color bottom = glm::mix(texel(levels, level, face, x0, y0 + 1),
                                texel(levels, level, face, x0 + 1, y0 + 1), fx);
  return glm::mix(top, bottom, fy);
}

// The per-pixel steps dDdx, dDdy of unit direction d projected onto its face, in texels of a
// w × h face: the square of the longer step. u = sc/ma changes by (dsc − u·dma)/ma.
float squaredTexelStep(const CubePoint& p, const Vec3& dDdx, const Vec3& dDdy, int w, int h) {
  const FaceAxes& axes = kFaceAxes[p.face];
  const float u = p.sc / p.ma, v = p.tc / p.ma;
  const float toS = 0.5f * static_cast<float>(w) / p.ma, toT = 0.5f * static_cast<float>(h) / p.ma;
  const auto squaredStep = [&](const Vec3& step) {
    const float dma = axes.signM * step[axes.m];
    const float ds = toS * (axes.signS * step[axes.s] - u * dma);
    const float dt = toT * (axes.signT * step[axes.t] - v * dma);
    return ds * ds + dt * dt;
  };
  return std::max(squaredStep(dDdx), squaredStep(dDdy));
}

// The lookups' footprints on one kind of levels, given the square of its width in texels of
// the finest level.
template <class Texels>
Color lookupBySquaredStep(const std::vector<std::array<Texels, 6>>& levels, const CubePoint& p,
                          float squaredStep) {
  // A step of at most a texel magnifies the finest level: no logarithm needed.
  if (!(squaredStep > 1.0f)) return blend(levels, 0, p.face, p.u(), p.v());
  const int top = static_cast<int>(levels.size()) - 1;
  const float lod = std::min(0.5f * std::log2(squaredStep), static_cast<float>(top));
  const int level = std::min(static_cast<int>(lod), top);
  const float weight = lod - static_cast<float>(level);  // of the coarser level
  const Color lower = blend(levels, level, p.face, p.u(), p.v());
  if (level == top || weight == 0.0f) return lower;
  return glm::mix(lower, blend(levels, level + 1, p.face, p.u(), p.v()), weight);
}

// CubeMap::lookup(d, dDdx, dDdy) on one kind of levels.
template <class Texels>
Color footprintLookup(const std::vector<std::array<Texels, 6>>& levels, const CubePoint& p,
                      const Vec3& dDdx, const Vec3& dDdy) {
  const Texels& finest = levels[0][p.face];
  return lookupBySquaredStep(levels, p,
                             squaredTexelStep(p, dDdx, dDdy, finest.width, finest.height));
}

// CubeMap::lookup(d, spread) on one kind of levels; d of unit length.
template <class Texels>
Color coneLookup(const std::vector<std::array<Texels, 6>>& levels, const CubePoint& p,
                 float spread) {
  const Texels& finest = levels[0][p.face];
  const float size = static_cast<float>(std::max(finest.width, finest.height));
  const float step = 0.5f * size * spread / (p.ma * p.ma);
  return lookupBySquaredStep(levels, p, step * step);
}

}  // namespace

CubeMap::CubeMap(CubeMapDesc desc) : scale_(desc.scale) {
  // Each face's pyramid on its own core (a 1024² face's takes about 10 ms).
  if (desc.keptAsBytes()) {
    std::array<std::vector<SrgbTexels>, 6> pyramids;
    parallelFor(6, 0, [&](uint64_t f) {
      pyramids[f] = srgbMipLevels(desc.srgbFaces[f]);
      desc.srgbFaces[f] = SrgbImage();  // freed as soon as its pyramid is built
    });
    srgbLevels_ = levelsOf(pyramids);
  } else {
    std::array<std::vector<ImageRgb>, 6> pyramids;
    parallelFor(6, 0, [&](uint64_t f) { pyramids[f] = mipLevels(std::move(desc.faces[f])); });
    linearLevels_ = levelsOf(pyramids);
  }
}

int CubeMap::levelCount() const {
  return static_cast<int>(keepsBytes() ? srgbLevels_.size() : linearLevels_.size());
}

CubeMap::FaceSize CubeMap::faceSize(int level, int face) const {
  if (keepsBytes()) return {srgbLevels_[level][face].width, srgbLevels_[level][face].height};
  return {linearLevels_[level][face].width, linearLevels_[level][face].height};
}

Color CubeMap::texelAt(int level, int face, int x, int y) const {
  return keepsBytes() ? srgbLevels_[level][face].at(x, y) : linearLevels_[level][face].at(x, y);
}

std::optional<CubeMap::FacePoint> CubeMap::facePoint(const Vec3& d) const {
  CubePoint p;
  if (!findCubePoint(d, p)) return std::nullopt;
  const FaceSize size = faceSize(0, p.face);
  return FacePoint{p.face, p.u() * static_cast<float>(size.width) - 0.5f,
                   p.v() * static_cast<float>(size.height) - 0.5f};
}

Color CubeMap::bilinear(int level, int face, float u, float v) const {
  return keepsBytes() ? blend(srgbLevels_, level, face, u, v)
                      : blend(linearLevels_, level, face, u, v);
}

Color CubeMap::lookup(const Vec3& d) const {
  CubePoint p;
  if (!findCubePoint(d, p)) return Color(0.0f);
  return scale_ * (keepsBytes() ? blend(srgbLevels_, 0, p.face, p.u(), p.v())
                                : blend(linearLevels_, 0, p.face, p.u(), p.v()));
}

float CubeMap::levelOfDetail(const Vec3& d, const Vec3& dDdx, const Vec3& dDdy) const {
  CubePoint p;
  if (!findCubePoint(d, p)) return -INFINITY;
  const FaceSize size = faceSize(0, p.face);
  return 0.5f * std::log2(squaredTexelStep(p, dDdx, dDdy, size.width, size.height));
}

Color CubeMap::lookup(const Vec3& d, const Vec3& dDdx, const Vec3& dDdy) const {
  CubePoint p;
  if (!findCubePoint(d, p)) return Color(0.0f);
  return scale_ * (keepsBytes() ? footprintLookup(srgbLevels_, p, dDdx, dDdy)
                                : footprintLookup(linearLevels_, p, dDdx, dDdy));
}

Color CubeMap::lookup(const Vec3& d, float spread) const {
  CubePoint p;
  if (!findCubePoint(d, p)) return Color(0.0f);
  return scale_ *
         (keepsBytes() ? coneLookup(srgbLevels_, p, spread) : coneLookup(linearLevels_, p, spread));
}

}  // namespace prism

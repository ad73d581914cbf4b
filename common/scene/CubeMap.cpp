#include "scene/CubeMap.h"

#include <algorithm>
#include <utility>

#include "math/FloorToInt.h"
#include "math/Simd.h"

namespace prism {

CubeMap::CubeMap(CubeMapDesc desc) : faces_(std::move(desc.faces)), scale_(desc.scale) {}

Color CubeMap::texel(int face, int x, int y) const {
  const ImageRgb& image = faces_[face];
  x = std::clamp(x, 0, image.width - 1);
  y = std::clamp(y, 0, image.height - 1);
  return image.at(x, y);
}

namespace {

// CubeMap::facePoint, inlined into lookup() (a call there cost 0.4 % of the default frame).
[[gnu::always_inline]] inline bool findFacePoint(const std::array<ImageRgb, 6>& faces,
                                                 const Vec3& d, CubeMap::FacePoint& point) {
  // OpenGL cube-map selection (OpenGL 4.6 spec, table 8.19): the major axis picks the face,
  // (sc, tc) / |ma| give the face coordinates in [-1, 1], t growing downwards in the image.
  const Vec3 a = absComponents(d);  // only compared, and a zero major axis fails
  int face;
  float sc, tc, ma;
  if (a.x >= a.y && a.x >= a.z) {
    face = d.x > 0.0f ? 0 : 1;
    ma = a.x;
    sc = d.x > 0.0f ? -d.z : d.z;
    tc = -d.y;
  } else if (a.y >= a.z) {
    face = d.y > 0.0f ? 2 : 3;
    ma = a.y;
    sc = d.x;
    tc = d.y > 0.0f ? d.z : -d.z;
  } else {
    face = d.z > 0.0f ? 4 : 5;
    ma = a.z;
    sc = d.z > 0.0f ? d.x : -d.x;
    tc = -d.y;
  }
  if (!(ma > 0.0f)) return false;
  const ImageRgb& image = faces[face];
  point = {face, 0.5f * (sc / ma + 1.0f) * static_cast<float>(image.width) - 0.5f,
           0.5f * (tc / ma + 1.0f) * static_cast<float>(image.height) - 0.5f};
  return true;
}

}  // namespace

std::optional<CubeMap::FacePoint> CubeMap::facePoint(const Vec3& d) const {
  FacePoint point;
  if (!findFacePoint(faces_, d, point)) return std::nullopt;
  return point;
}

Color CubeMap::lookup(const Vec3& d) const {
  FacePoint point;
  if (!findFacePoint(faces_, d, point)) return Color(0.0f);
  const int face = point.face;
  const float s = point.s, t = point.t;
  const ImageRgb& image = faces_[face];
  const int x0 = floorToInt<int>(s);
  const int y0 = floorToInt<int>(t);
  const float fx = s - static_cast<float>(x0);
  const float fy = t - static_cast<float>(y0);
  // Inside the face (nearly every lookup) the four texels need no clamping, and each is read as
  // four lanes (its three channels and a neighbour's first, unused), so the three blends of
  // glm::mix, a·(1 − f) + b·f, take one vector operation per step instead of three: the same
  // roundings channel by channel. The face's last texel is never read this way, so no lane
  // reads past the image.
  const int w = image.width, h = image.height;
  if (x0 >= 0 && y0 >= 0 && x0 + 1 < w && y0 + 1 < h && !(x0 + 2 == w && y0 + 2 == h)) {
    const Color* texels = &image.pixels[static_cast<size_t>(y0) * w + x0];
    const auto lanes = [](const Color* c) { return simd::load<simd::Float4>(&c->x); };
    const simd::Float4 top = lanes(texels) * (1.0f - fx) + lanes(texels + 1) * fx;
    const simd::Float4 bottom = lanes(texels + w) * (1.0f - fx) + lanes(texels + w + 1) * fx;
    const simd::Float4 blend = scale_ * (top * (1.0f - fy) + bottom * fy);
    return Color(blend[0], blend[1], blend[2]);
  }
  const Color top = glm::mix(texel(face, x0, y0), texel(face, x0 + 1, y0), fx);
  const Color bottom = glm::mix(texel(face, x0, y0 + 1), texel(face, x0 + 1, y0 + 1), fx);
  return scale_ * glm::mix(top, bottom, fy);
}

}  // namespace prism

// A ray's footprint as a cone (Akenine-Möller et al. 2021, "Improved shader and texture level of
// detail using ray cones"): two floats a ray where a ray differential carries twelve. At distance
// t along the ray the cone is width + spread·t wide (its sign: a cone focused by a curved surface
// narrows through zero and widens again). Textures read the mip level whose texels match the
// width where the ray meets them; the sky reads the level its spread asks for.
//
// Flat surfaces pass a cone on unturned; a sphere turns it by its curvature (reflection: twice
// the surface's turn over the width, refraction: Igehy's first-order rule on the width);
// smooth-shaded meshes and other curved surfaces end it, and what lies past them is read at its
// finest level, as with differentials.
#pragma once

#include <cmath>
#include <limits>

namespace prism {

struct RayCone {
  float width = 0.0f;
  float spread = std::numeric_limits<float>::infinity();  // infinite: no cone (finest level)

  bool known() const { return spread < std::numeric_limits<float>::infinity(); }
  float widthAt(float t) const { return std::fabs(width + spread * t); }

  // The cone leaving a surface it met at distance t. curvature: ±1/R of a sphere (+ where the
  // normal facing the ray points out of it), 0 for a flat surface. cosine: of the angle between
  // the ray and that normal.
  RayCone reflected(float t, float curvature) const {
    const float w = width + spread * t;
    return {w, spread + 2.0f * curvature * std::fabs(w)};
  }
  // eta: ratio of the indices (incident over transmitted); cosI, cosT: the angles' cosines.
  RayCone refracted(float t, float curvature, float eta, float cosI, float cosT) const {
    const float w = width + spread * t;
    return {w, eta * spread + (eta * cosI - cosT) * curvature * std::fabs(w)};
  }
};

}  // namespace prism

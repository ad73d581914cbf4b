#include "caustics/MirrorCausticEstimator.h"

#include <cmath>
#include <stdexcept>

#include "math/RayOffset.h"
#include "shading/LightFalloff.h"

namespace prism {
namespace {

bool casts(CausticRole role, const MaterialDesc& m) {
  return (causticFlags(role, m) & kCastsCaustics) != 0;
}

std::string mirrorProblem(const MaterialDesc& m) {
  if (m.transmittance.x > 0.0f || m.transmittance.y > 0.0f || m.transmittance.z > 0.0f) {
    return "material '" + m.name + "' transmits light";
  }
  return "";
}

}  // namespace

MirrorCausticEstimator::MirrorCausticEstimator(const SceneDescription& d, const Scene& scene)
    : scene_(scene), lights_(d.lights) {
  const auto refuse = [](const std::string& why) {
    throw std::invalid_argument("no analytic caustics for this scene: " + why +
                                " (the closed form covers flat mirrors in one plane)");
  };
  forEachShapeList(d, [&](const auto& shapes) {
    for (const auto& shape : shapes) {
      if (casts(shape.caustic, d.materials[shape.material])) {
        refuse("a " + std::string(shape.kName) + " casts caustics");
      }
    }
  });
  for (const PlaneDesc& p : d.planes) {
    const MaterialDesc& m = d.materials[p.material];
    if (!casts(p.caustic, m)) continue;
    if (const std::string why = mirrorProblem(m); !why.empty()) refuse(why);
    facets_.push_back({Vec3(0.0f), Vec3(0.0f), Vec3(0.0f), true, p.normal,
                       glm::dot(p.normal, p.point), m.reflectance});
  }
  for (const MeshDesc& mesh : d.meshes) {
    const MaterialDesc& m = d.materials[mesh.material];
    if (!casts(mesh.caustic, m)) continue;
    if (const std::string why = mirrorProblem(m); !why.empty()) refuse(why);
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const Vec3 v0 = mesh.positions[mesh.indices[t]];
      const Vec3 e1 = mesh.positions[mesh.indices[t + 1]] - v0;
      const Vec3 e2 = mesh.positions[mesh.indices[t + 2]] - v0;
      const Vec3 cross = glm::cross(e1, e2);
      const float area2 = glm::length(cross);
      if (!(area2 > 0.0f)) continue;  // degenerate: reflects nothing
      const Vec3 normal = cross / area2;
      if (!mesh.normals.empty()) {
        for (int k = 0; k < 3; ++k) {
          const Vec3 n = glm::normalize(mesh.normals[mesh.indices[t + k]]);
          if (std::abs(glm::dot(n, normal)) < 1.0f - 1e-5f) refuse("a mirror is smooth-shaded");
        }
      }
      facets_.push_back({v0, e1, e2, false, normal, glm::dot(normal, v0), m.reflectance});
    }
  }
  // One plane for all: then no facet can send light to another.
  const float scale = std::max(1.0f, glm::length(scene.bounds().extent()));
  for (const Facet& f : facets_) {
    const Facet& first = facets_.front();
    const float alignment = glm::dot(f.normal, first.normal);
    const float offset = alignment > 0.0f ? f.offset : -f.offset;
    if (std::abs(alignment) < 1.0f - 1e-5f || std::abs(offset - first.offset) > 1e-5f * scale) {
      refuse("the mirrors do not lie in one plane");
    }
  }
}

bool MirrorCausticEstimator::insideFacet(const Facet& f, const Vec3& point) const {
  if (f.unbounded) return true;
  // Barycentric coordinates of a point on the triangle's plane.
  const Vec3 w = point - f.v0;
  const float d00 = glm::dot(f.e1, f.e1), d01 = glm::dot(f.e1, f.e2), d11 = glm::dot(f.e2, f.e2);
  const float d20 = glm::dot(w, f.e1), d21 = glm::dot(w, f.e2);
  const float denominator = d00 * d11 - d01 * d01;
  const float v = (d11 * d20 - d01 * d21) / denominator;
  const float u = (d00 * d21 - d01 * d20) / denominator;
  return v >= 0.0f && u >= 0.0f && u + v <= 1.0f;
}

bool MirrorCausticEstimator::unblocked(const Vec3& origin, const Vec3& mirrorPoint) const {
  const Vec3 along = mirrorPoint - origin;
  const float distance = glm::length(along);
  if (!(distance > 0.0f)) return true;
  Ray ray;
  ray.origin = origin;
  ray.direction = along / distance;
  // Stop short of the mirror itself.
  ray.tMax = distance * (1.0f - 1e-4f);
  return !scene_.occluded(ray);
}

Color MirrorCausticEstimator::irradiance(const Vec3& position, const Vec3& normal) const {
  return irradianceWithin(position, normal, leavingDistance(position, Vec3(0.0f), normal));
}

Color MirrorCausticEstimator::irradianceAt(const SurfaceHit& s, const PixelFootprint&) const {
  return irradianceWithin(s.position, s.geometricNormal, s.leavingDistance);
}

Color MirrorCausticEstimator::irradianceWithin(const Vec3& p, const Vec3& n, float leaving) const {
  Color total(0.0f);
  for (const PointLightDesc& light : lights_) {
    for (const Facet& f : facets_) {
      const float lightSide = glm::dot(f.normal, light.position) - f.offset;
      const float pointSide = glm::dot(f.normal, p) - f.offset;
      if (lightSide == 0.0f || !(lightSide * pointSide > 0.0f)) continue;
      const Vec3 image = light.position - 2.0f * lightSide * f.normal;
      // The segment image → p crosses the plane at the fraction lightSide / (lightSide +
      // pointSide).
      const Vec3 m = image + (p - image) * (lightSide / (lightSide + pointSide));
      if (!insideFacet(f, m)) continue;
      const Vec3 toMirror = m - p;
      const float toMirrorLength = glm::length(toMirror);
      if (!(toMirrorLength > 0.0f)) continue;
      const float cosine = glm::dot(n, toMirror) / toMirrorLength;
      if (!(cosine > 0.0f)) continue;
      const float lightToMirror = glm::length(m - light.position);
      const float path = lightToMirror + toMirrorLength;
      const Vec3 receiverOrigin = leavingOrigin(p, n, leaving, toMirror / toMirrorLength);
      if (!unblocked(receiverOrigin, m) || !unblocked(light.position, m)) continue;
      total += f.reflectance * light.intensity *
               (falloffRelativeToInverseSquare(light.attenuation, lightToMirror) * cosine /
                (path * path));
    }
  }
  return total;
}

}  // namespace prism

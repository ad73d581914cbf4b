#include "render/DebugShading.h"

namespace prism {

Color debugColor(const Scene& scene, const Ray& ray, DebugView view, RayCounters& counters) {
  ++counters.primary;
  HitRecord hit;
  if (!scene.intersect(ray, hit)) return Color(0.0f);
  const SurfaceHit surface = scene.surface(ray, hit);
  switch (view) {
    case DebugView::Normals:
      return 0.5f * (surface.shadingNormal + Vec3(1.0f));
    case DebugView::Image:
      break;  // not a debug view: the TileRenderer traces radiance instead
  }
  return Color(0.0f);
}

}  // namespace prism

// Colours for the viewer's debug views: what the first hit along a camera ray is, not how
// much light it carries.
#pragma once

#include "render/RayCounters.h"
#include "render/RenderView.h"
#include "scene/Scene.h"

namespace prism {

// The debug colour seen along a primary ray; black where the ray escapes. Counts the ray.
Color debugColor(const Scene& scene, const Ray& ray, DebugView view, RayCounters& counters);

}  // namespace prism

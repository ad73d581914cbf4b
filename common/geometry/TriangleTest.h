// Which ray-triangle test finds triangle hits: the scene setting `triangle_test`
// (scene/SettingNames.h names them). Every test finds the same hits up to rounding; the
// watertight one leaves no cracks along shared edges (geometry/TriangleWatertight.h).
#pragma once

namespace prism {

enum class TriangleTest { MollerTrumbore, PlaneThenInside, Watertight };

}  // namespace prism

// This copy's geometry kernels (compiled once per instruction set; accel/IsaVariant.h).
#include "accel/IsaVariant.h"
#include "accel/SceneGeometry.h"

extern "C" const prism::GeometryKernels PRISM_ISA_ENTRY(geometry) = {
    prism::kCompiledInstructionSet,
    static_cast<int>(sizeof(prism::simd::PacketVector) / sizeof(float)),
    &prism::SceneGeometry::Kernels::intersect,
    &prism::SceneGeometry::Kernels::occluded,
    &prism::SceneGeometry::Kernels::intersect8,
    &prism::SceneGeometry::Kernels::occluded8,
    &prism::SceneGeometry::Kernels::surface};

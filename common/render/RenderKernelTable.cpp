// This copy's tile renderer (compiled once per instruction set; accel/IsaVariant.h).
#include "accel/IsaVariant.h"
#include "render/RenderKernels.h"
#include "render/TileRenderer.h"

extern "C" const prism::RenderKernels PRISM_ISA_ENTRY(render) = {
    prism::kCompiledInstructionSet, &prism::TileRenderer::Kernels::render};

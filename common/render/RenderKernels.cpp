#include "render/RenderKernels.h"

// Each set's table, defined by render/RenderKernelTable.cpp in that set's copy.
extern "C" const prism::RenderKernels prism_isa_baseline_render;
#if defined(PRISM_HAVE_ISA_VARIANTS)
extern "C" const prism::RenderKernels prism_isa_v2_render;
extern "C" const prism::RenderKernels prism_isa_v3_render;
extern "C" const prism::RenderKernels prism_isa_v4_render;
#endif

namespace prism {

const RenderKernels& renderKernels(InstructionSet isa) {
#if defined(PRISM_HAVE_ISA_VARIANTS)
  static const RenderKernels* const kTables[4] = {&prism_isa_baseline_render, &prism_isa_v2_render,
                                                  &prism_isa_v3_render, &prism_isa_v4_render};
#else
  static const RenderKernels* const kTables[4] = {&prism_isa_baseline_render, nullptr, nullptr,
                                                  nullptr};
#endif
  return tableForSet(isa, kTables, "render kernels");
}

}  // namespace prism

#include "render/RenderKernels.h"

#include <stdexcept>
#include <string>

// Each set's table, defined by render/RenderKernelTable.cpp in that set's copy.
extern "C" const prism::RenderKernels prism_isa_baseline_render;
#if defined(PRISM_HAVE_ISA_VARIANTS)
extern "C" const prism::RenderKernels prism_isa_v2_render;
extern "C" const prism::RenderKernels prism_isa_v3_render;
extern "C" const prism::RenderKernels prism_isa_v4_render;
#endif

namespace prism {

const RenderKernels& renderKernels(InstructionSet isa) {
  switch (isa) {
    case InstructionSet::Baseline:
      return prism_isa_baseline_render;
#if defined(PRISM_HAVE_ISA_VARIANTS)
    case InstructionSet::V2:
      return prism_isa_v2_render;
    case InstructionSet::V3:
      return prism_isa_v3_render;
    case InstructionSet::V4:
      return prism_isa_v4_render;
#endif
    default:
      break;
  }
  throw std::invalid_argument(std::string("no render kernels for ") + instructionSetName(isa));
}

}  // namespace prism

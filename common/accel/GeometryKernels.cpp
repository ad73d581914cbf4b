#include "accel/GeometryKernels.h"

#include <stdexcept>
#include <string>

// Each set's table, defined by accel/GeometryKernelTable.cpp in that set's copy.
extern "C" const prism::GeometryKernels prism_isa_baseline_geometry;
#if defined(PRISM_HAVE_ISA_VARIANTS)
extern "C" const prism::GeometryKernels prism_isa_v2_geometry;
extern "C" const prism::GeometryKernels prism_isa_v3_geometry;
extern "C" const prism::GeometryKernels prism_isa_v4_geometry;
#endif

namespace prism {

const GeometryKernels& geometryKernels(InstructionSet isa) {
  switch (isa) {
    case InstructionSet::Baseline:
      return prism_isa_baseline_geometry;
#if defined(PRISM_HAVE_ISA_VARIANTS)
    case InstructionSet::V2:
      return prism_isa_v2_geometry;
    case InstructionSet::V3:
      return prism_isa_v3_geometry;
    case InstructionSet::V4:
      return prism_isa_v4_geometry;
#endif
    default:
      break;
  }
  throw std::invalid_argument(std::string("no geometry kernels for ") + instructionSetName(isa));
}

}  // namespace prism

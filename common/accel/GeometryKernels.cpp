#include "accel/GeometryKernels.h"

// Each set's table, defined by accel/GeometryKernelTable.cpp in that set's copy.
extern "C" const prism::GeometryKernels prism_isa_baseline_geometry;
#if defined(PRISM_HAVE_ISA_VARIANTS)
extern "C" const prism::GeometryKernels prism_isa_v2_geometry;
extern "C" const prism::GeometryKernels prism_isa_v3_geometry;
extern "C" const prism::GeometryKernels prism_isa_v4_geometry;
#endif

namespace prism {

const GeometryKernels& geometryKernels(InstructionSet isa) {
#if defined(PRISM_HAVE_ISA_VARIANTS)
  static const GeometryKernels* const kTables[4] = {&prism_isa_baseline_geometry,
                                                    &prism_isa_v2_geometry, &prism_isa_v3_geometry,
                                                    &prism_isa_v4_geometry};
#else
  static const GeometryKernels* const kTables[4] = {&prism_isa_baseline_geometry, nullptr, nullptr,
                                                    nullptr};
#endif
  return tableForSet(isa, kTables, "geometry kernels");
}

}  // namespace prism

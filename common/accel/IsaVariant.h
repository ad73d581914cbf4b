// For sources compiled once per instruction set (CMakeLists.txt, "Kernels per instruction set"):
// which set this copy is compiled for, and the name of its entry point. The build defines
// PRISM_ISA_SUFFIX (v2, v3, v4) and PRISM_ISA_LEVEL (InstructionSet's number) for the
// variants; the copy in prism_core itself is the baseline. An entry point is the one symbol of
// a variant left visible: extern "C", named prism_isa_<suffix>_<what>.
#pragma once

#include "util/InstructionSet.h"

#ifndef PRISM_ISA_SUFFIX
#define PRISM_ISA_SUFFIX baseline
#define PRISM_ISA_LEVEL 1
#endif

#define PRISM_ISA_JOIN3(a, b, c) a##b##c
#define PRISM_ISA_EXPAND3(a, b, c) PRISM_ISA_JOIN3(a, b, c)
// PRISM_ISA_ENTRY(geometry) names prism_isa_v3_geometry in the v3 copy.
#define PRISM_ISA_ENTRY(what) PRISM_ISA_EXPAND3(prism_isa_, PRISM_ISA_SUFFIX, _##what)

namespace prism {
inline constexpr InstructionSet kCompiledInstructionSet =
    static_cast<InstructionSet>(PRISM_ISA_LEVEL);
}  // namespace prism

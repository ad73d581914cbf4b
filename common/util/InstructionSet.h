// The instruction sets the ray kernels are compiled for, and which of them this process runs.
// The kernels (accel/SceneGeometry.h's walks and leaf tests) are built once per instruction set,
// each as whole translation units (CMakeLists.txt, "Kernels per instruction set"): the build's
// own target (x86-64, SSE2) and, on x86-64, x86-64-v2, x86-64-v3 (AVX2, FMA) and x86-64-v4
// (AVX-512). A job runs one of them on every rank (rank 0 chooses; docs/performance.md), so
// its pixels do not depend on which machine traced them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace prism {

// In order of what they assume: each runs wherever the next one does.
enum class InstructionSet : uint8_t {
  Auto = 0,      // a choice, not a set: the best that every rank of the job runs
  Baseline = 1,  // what the build targets (x86-64: SSE2; elsewhere the compiler's default)
  V2 = 2,        // x86-64-v2: SSE4.2, POPCNT
  V3 = 3,        // x86-64-v3: AVX2, FMA, BMI2
  V4 = 4         // x86-64-v4: AVX-512 F, BW, CD, DQ, VL
};

// Sets of instruction sets, one bit each (bit n: the set numbered n).
using InstructionSetMask = uint32_t;
constexpr InstructionSetMask maskOf(InstructionSet isa) {
  return InstructionSetMask{1} << static_cast<unsigned>(isa);
}

// "auto", "x86-64", "x86-64-v2", "x86-64-v3", "x86-64-v4" (the build's own on other machines:
// "baseline").
const char* instructionSetName(InstructionSet isa);
// The names above, and their short forms "baseline", "v2", "v3", "v4"; nothing for others.
std::optional<InstructionSet> parseInstructionSet(std::string_view text);

// The sets this process can run: compiled into this binary and supported by this CPU (and its
// operating system, for AVX state). Always holds Baseline. The environment variable
// PRISM_TEST_CPU_LIMIT (a name above) caps it, so that tests can play a rank on an older CPU.
InstructionSetMask runnableInstructionSets();
// The concrete sets in mask, from the baseline up.
std::vector<InstructionSet> instructionSetsIn(InstructionSetMask mask);
// The best set in mask (Baseline for an empty one).
InstructionSet bestInstructionSet(InstructionSetMask mask);
// Auto resolved to the best this process runs; a concrete set it cannot run throws
// std::invalid_argument naming what this CPU runs.
InstructionSet resolveInstructionSet(InstructionSet requested);

// One of a table per concrete set (the kernels' entry points): tables[isa - Baseline], null where
// this binary has none. Throws std::invalid_argument naming `what` and the set.
const void* tableForSet(InstructionSet isa, const void* const (&tables)[4], const char* what);
template <class Table>
const Table& tableForSet(InstructionSet isa, const Table* const (&tables)[4], const char* what) {
  const void* const erased[4] = {tables[0], tables[1], tables[2], tables[3]};
  return *static_cast<const Table*>(tableForSet(isa, erased, what));
}

// The model name of this machine's CPU ("AMD EPYC 7B13"; at most kMaxCpuNameBytes), or
// "unknown CPU": how messages name a rank's machine.
inline constexpr size_t kMaxCpuNameBytes = 256;
std::string cpuModelName();

}  // namespace prism

#include "util/InstructionSet.h"

#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

namespace prism {
namespace {

struct NamedSet {
  std::string_view name, shortName;
  InstructionSet isa;
};

constexpr NamedSet kNames[] = {{"auto", "auto", InstructionSet::Auto},
#if defined(__x86_64__)
                               {"x86-64", "baseline", InstructionSet::Baseline},
#else
                               {"baseline", "baseline", InstructionSet::Baseline},
#endif
                               {"x86-64-v2", "v2", InstructionSet::V2},
                               {"x86-64-v3", "v3", InstructionSet::V3},
                               {"x86-64-v4", "v4", InstructionSet::V4}};

// The sets this binary has kernels for (CMakeLists.txt builds the variants on x86-64 unless a
// target is forced with PRISM_ARCH, or for the fuzzers).
constexpr InstructionSetMask kBuiltSets =
#if defined(PRISM_HAVE_ISA_VARIANTS)
    maskOf(InstructionSet::V2) | maskOf(InstructionSet::V3) | maskOf(InstructionSet::V4) |
#endif
    maskOf(InstructionSet::Baseline);

// What the CPU offers, level by level (the levels are nested: v3 needs everything v2 needs).
InstructionSetMask cpuSets() {
  InstructionSetMask mask = maskOf(InstructionSet::Baseline);
#if defined(__x86_64__)
  __builtin_cpu_init();
  const bool v2 = __builtin_cpu_supports("sse3") && __builtin_cpu_supports("ssse3") &&
                  __builtin_cpu_supports("sse4.1") && __builtin_cpu_supports("sse4.2") &&
                  __builtin_cpu_supports("popcnt");
  // The AVX features are reported only where the operating system saves their registers.
  const bool v3 = v2 && __builtin_cpu_supports("avx") && __builtin_cpu_supports("avx2") &&
                  __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
                  __builtin_cpu_supports("bmi2");
  const bool v4 = v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                  __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
                  __builtin_cpu_supports("avx512vl");
  if (v2) mask |= maskOf(InstructionSet::V2);
  if (v3) mask |= maskOf(InstructionSet::V3);
  if (v4) mask |= maskOf(InstructionSet::V4);
#endif
  return mask;
}

InstructionSetMask computeRunnable() {
  InstructionSetMask mask = cpuSets() & kBuiltSets;
  if (const char* limit = std::getenv("PRISM_TEST_CPU_LIMIT"); limit && *limit) {
    const std::optional<InstructionSet> cap = parseInstructionSet(limit);
    if (!cap || *cap == InstructionSet::Auto) {
      throw std::invalid_argument(std::string("PRISM_TEST_CPU_LIMIT: not an instruction set: ") +
                                  limit);
    }
    mask &= maskOf(*cap) | (maskOf(*cap) - 1);  // the cap and everything below it
  }
  return mask;
}

}  // namespace

const char* instructionSetName(InstructionSet isa) {
  for (const NamedSet& n : kNames) {
    if (n.isa == isa) return n.name.data();
  }
  return "unknown";
}

std::optional<InstructionSet> parseInstructionSet(std::string_view text) {
  for (const NamedSet& n : kNames) {
    if (text == n.name || text == n.shortName) return n.isa;
  }
  return std::nullopt;
}

InstructionSetMask runnableInstructionSets() {
  static const InstructionSetMask mask = computeRunnable();
  return mask;
}

std::vector<InstructionSet> instructionSetsIn(InstructionSetMask mask) {
  std::vector<InstructionSet> sets;
  for (InstructionSet isa :
       {InstructionSet::Baseline, InstructionSet::V2, InstructionSet::V3, InstructionSet::V4}) {
    if (mask & maskOf(isa)) sets.push_back(isa);
  }
  return sets;
}

InstructionSet bestInstructionSet(InstructionSetMask mask) {
  for (InstructionSet isa : {InstructionSet::V4, InstructionSet::V3, InstructionSet::V2}) {
    if (mask & maskOf(isa)) return isa;
  }
  return InstructionSet::Baseline;
}

InstructionSet resolveInstructionSet(InstructionSet requested) {
  const InstructionSetMask runnable = runnableInstructionSets();
  if (requested == InstructionSet::Auto) return bestInstructionSet(runnable);
  if (!(kBuiltSets & maskOf(requested))) {
    throw std::invalid_argument(std::string("instruction set ") + instructionSetName(requested) +
                                ": this build has no kernels for it (built with PRISM_ARCH, "
                                "for the fuzzers, or not for x86-64)");
  }
  if (!(runnable & maskOf(requested))) {
    throw std::invalid_argument(std::string("instruction set ") + instructionSetName(requested) +
                                ": this CPU runs at most " +
                                instructionSetName(bestInstructionSet(runnable)));
  }
  return requested;
}

const void* tableForSet(InstructionSet isa, const void* const (&tables)[4], const char* what) {
  const int index = static_cast<int>(isa) - static_cast<int>(InstructionSet::Baseline);
  if (index >= 0 && index < 4 && tables[index] != nullptr) return tables[index];
  throw std::invalid_argument(std::string("no ") + what + " for " + instructionSetName(isa));
}

std::string cpuModelName() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) break;
    const size_t first = line.find_first_not_of(" \t", colon + 1);
    if (first == std::string::npos) break;
    return line.substr(first, kMaxCpuNameBytes);
  }
  return "unknown CPU";
}

}  // namespace prism

// The memory limit a process applies when the user gave none: its machine's physical memory.
// Each rank asks its own machine, so uneven nodes each refuse what they cannot hold.
#pragma once

#include <cstdint>
#include <optional>

#include "util/MemorySize.h"

namespace prism {

// Physical memory of this machine in bytes (UINT64_MAX when the system cannot say).
uint64_t physicalMemoryBytes();

// The limit a run was given (--memory-limit), or this machine's physical memory.
MemoryLimit memoryLimitOrPhysical(const std::optional<uint64_t>& givenBytes);

}  // namespace prism

#include "util/PhysicalMemory.h"

#include <unistd.h>

namespace prism {

uint64_t physicalMemoryBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long pageSize = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || pageSize <= 0) return UINT64_MAX;
  return static_cast<uint64_t>(pages) * static_cast<uint64_t>(pageSize);
}

MemoryLimit memoryLimitOrPhysical(const std::optional<uint64_t>& givenBytes) {
  if (givenBytes) return {*givenBytes, "--memory-limit"};
  return {physicalMemoryBytes(), "this machine's memory; --memory-limit SIZE changes it"};
}

}  // namespace prism

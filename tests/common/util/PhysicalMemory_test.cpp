#include "util/PhysicalMemory.h"

#include <gtest/gtest.h>
#include <unistd.h>

namespace prism {
namespace {

TEST(PhysicalMemory, IsThePagesTheSystemReports) {
  EXPECT_EQ(physicalMemoryBytes(), static_cast<uint64_t>(::sysconf(_SC_PHYS_PAGES)) *
                                       static_cast<uint64_t>(::sysconf(_SC_PAGE_SIZE)));
}

TEST(PhysicalMemory, AGivenLimitWinsAndSaysWhereItCameFrom) {
  const MemoryLimit given = memoryLimitOrPhysical(uint64_t{1} << 20);
  EXPECT_EQ(given.bytes, uint64_t{1} << 20);
  EXPECT_EQ(given.source, "--memory-limit");
  const MemoryLimit physical = memoryLimitOrPhysical(std::nullopt);
  EXPECT_EQ(physical.bytes, physicalMemoryBytes());
  EXPECT_EQ(physical.source, "this machine's memory; --memory-limit SIZE changes it");
}

}  // namespace
}  // namespace prism

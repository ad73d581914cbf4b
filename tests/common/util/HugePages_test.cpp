#include "util/HugePages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace prism {
namespace {

// The kernel's transparent huge page mode ("always", "madvise" or "never"), empty without THP.
std::string transparentHugePageMode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(in, line);
  const size_t open = line.find('['), close = line.find(']');
  if (open == std::string::npos || close == std::string::npos) return {};
  return line.substr(open + 1, close - open - 1);
}

// The VmFlags line of the mapping in /proc/self/smaps that holds `address`.
std::string vmFlagsAt(const void* address) {
  const uintptr_t at = reinterpret_cast<uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream range(line);
    if (range >> std::hex >> begin >> dash >> end && dash == '-') {
      inside = begin <= at && at < end;
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      return line;
    }
  }
  return {};
}

TEST(HugePages, AReservedLargeArrayIsAdvisedBeforeItsFirstWrite) {
  const std::string mode = transparentHugePageMode();
  if (mode.empty() || mode == "never") GTEST_SKIP() << "no transparent huge pages here";
  std::vector<float> values;
  reserveOnHugePages(values, size_t{16} << 20);  // 64 MiB
  ASSERT_GE(values.capacity(), size_t{16} << 20);
  // A 2 MiB-aligned address inside the array: madvise split its mapping there ("hg" = advised).
  const uintptr_t aligned =
      (reinterpret_cast<uintptr_t>(values.data()) + (size_t{4} << 20)) & ~((size_t{2} << 20) - 1);
  const std::string flags = vmFlagsAt(reinterpret_cast<const void*>(aligned));
  ASSERT_FALSE(flags.empty()) << "no mapping found in /proc/self/smaps";
  EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;
  values.resize(values.capacity(), 1.0f);  // usable as usual
  EXPECT_EQ(values.back(), 1.0f);
}

TEST(HugePages, SmallAndEmptyRangesAreLeftAlone) {
  preferHugePages(nullptr, size_t{64} << 20);
  int one = 0;
  preferHugePages(&one, sizeof(one));
  std::vector<int> none;
  reserveOnHugePages(none, 0);
  EXPECT_TRUE(none.empty());
  std::vector<int> small;
  reserveOnHugePages(small, 1000);
  small.assign(1000, 7);
  EXPECT_EQ(small[999], 7);
}

// A HugePageVector of a huge page or more starts on a 2 MiB boundary, and its first huge page is
// advised where the kernel takes advice; smaller ones are ordinary. Both hold what is put in,
// through growth (reallocation moves between the two kinds of block) and copies.
TEST(HugePages, AHugePageVectorStartsOnAHugePage) {
  HugePageVector<float> large(size_t{1} << 20, 2.0f);  // 4 MiB
  EXPECT_EQ(reinterpret_cast<uintptr_t>(large.data()) % kHugePageBytes, 0u);
  const std::string mode = transparentHugePageMode();
  if (!mode.empty() && mode != "never") {
    const std::string flags = vmFlagsAt(large.data());
    ASSERT_FALSE(flags.empty()) << "no mapping found in /proc/self/smaps";
    EXPECT_NE(flags.find(" hg"), std::string::npos) << flags;
  }
  HugePageVector<float> grown(10, 3.0f);
  for (size_t i = 0; i < (size_t{3} << 20); ++i) grown.push_back(static_cast<float>(i));
  EXPECT_EQ(reinterpret_cast<uintptr_t>(grown.data()) % kHugePageBytes, 0u);
  EXPECT_EQ(grown[9], 3.0f);
  EXPECT_EQ(grown.back(), static_cast<float>((size_t{3} << 20) - 1));
  const HugePageVector<float> copy = large;
  EXPECT_EQ(copy.size(), large.size());
  EXPECT_EQ(copy.back(), 2.0f);
  grown.resize(5);
  grown.shrink_to_fit();  // back to an ordinary block
  EXPECT_EQ(grown[4], 3.0f);
}

}  // namespace
}  // namespace prism

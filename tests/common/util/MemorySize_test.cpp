#include "util/MemorySize.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace prism {
namespace {

TEST(MemorySize, ParsesBinaryUnitsCaseInsensitively) {
  EXPECT_EQ(parseMemorySize("8G"), 8589934592ull);
  EXPECT_EQ(parseMemorySize("512M"), 536870912ull);
  EXPECT_EQ(parseMemorySize("512m"), 536870912ull);
  EXPECT_EQ(parseMemorySize("1.5T"), 1649267441664ull);
  EXPECT_EQ(parseMemorySize("64k"), 65536ull);
  EXPECT_EQ(parseMemorySize("2GiB"), 2147483648ull);
  EXPECT_EQ(parseMemorySize("2 GB"), 2147483648ull);
  EXPECT_EQ(parseMemorySize("1000000"), 1000000ull);
  EXPECT_EQ(parseMemorySize("100B"), 100ull);
  EXPECT_EQ(parseMemorySize("99999E"), UINT64_MAX);  // past 2^64: no limit at all
}

TEST(MemorySize, RefusesWhatIsNotASize) {
  for (const char* text : {"", "G", "abc", "0", "-1G", "5X", "8GG", "nan", "inf", "0.1"}) {
    EXPECT_THROW(parseMemorySize(text), std::invalid_argument) << text;
  }
  try {
    parseMemorySize("12Q");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "--memory-limit: '12Q' is not a size (examples: 512M, 8G, 1.5T, 1000000)");
  }
}

TEST(MemorySize, FormatsBytesInBinaryUnits) {
  EXPECT_EQ(formatBytes(512), "512 B");
  EXPECT_EQ(formatBytes(1536), "1.5 KiB");
  EXPECT_EQ(formatBytes(3.0 * (1ull << 30)), "3.0 GiB");
}

TEST(MemorySize, ArithmeticSaturatesInsteadOfWrapping) {
  EXPECT_EQ(saturatingMultiply(1ull << 40, 1ull << 40), UINT64_MAX);
  EXPECT_EQ(saturatingMultiply(0, UINT64_MAX), 0u);
  EXPECT_EQ(saturatingMultiply(3, 4), 12u);
  EXPECT_EQ(saturatingAdd(UINT64_MAX - 1, 5), UINT64_MAX);
  EXPECT_EQ(saturatingAdd(2, 3), 5u);
}

TEST(MemorySize, RefusalNamesTheNeedAndTheLimitInBytes) {
  EXPECT_EQ(
      memoryRefusal("a thing", 3ull << 30, MemoryLimit{1ull << 30, "--memory-limit"}, "do less"),
      "a thing needs 3.0 GiB (3221225472 bytes); the memory limit is 1.0 GiB (1073741824 "
      "bytes, --memory-limit): do less");
}

}  // namespace
}  // namespace prism

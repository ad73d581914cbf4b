#include "util/SelectNth.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace prism {
namespace {

// Every rank of arrays of every size up to 300, drawn from wide, narrow (many repeats) and
// constant value sets: the selected value is the sorted array's, nothing before it is larger and
// nothing after it smaller, and the array holds the same values as before.
TEST(SelectNth, EveryRankMatchesTheSortedArray) {
  std::mt19937 rng(3);
  for (int distinct : {1000000, 7, 1}) {
    std::uniform_int_distribution<int> value(0, distinct - 1);
    for (size_t count : {1u, 2u, 3u, 16u, 17u, 40u, 301u}) {
      std::vector<float> values(count);
      for (float& v : values) v = 0.25f * static_cast<float>(value(rng));
      std::vector<float> sorted = values;
      std::sort(sorted.begin(), sorted.end());
      for (size_t nth = 0; nth < count; ++nth) {
        std::vector<float> a = values;
        selectNth(a.data(), a.size(), nth);
        ASSERT_EQ(a[nth], sorted[nth]) << "count " << count << ", nth " << nth;
        for (size_t i = 0; i < nth; ++i) ASSERT_LE(a[i], a[nth]);
        for (size_t i = nth + 1; i < count; ++i) ASSERT_GE(a[i], a[nth]);
        std::sort(a.begin(), a.end());
        ASSERT_EQ(a, sorted);
      }
    }
  }
}

// Selecting on a prefix leaves the rest alone, and ranks selected largest first stay in place:
// what photonRadii relies on for the automatic k's ladder.
TEST(SelectNth, RanksSelectedLargestFirstStayInPlace) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  std::vector<float> a(700);
  for (float& v : a) v = value(rng);
  std::vector<float> sorted = a;
  std::sort(sorted.begin(), sorted.end());
  size_t end = a.size();
  for (size_t rank : {400u, 256u, 128u, 64u, 32u, 16u, 8u}) {
    selectNth(a.data(), end, rank - 1);
    end = rank - 1;
  }
  for (size_t rank : {400u, 256u, 128u, 64u, 32u, 16u, 8u})
    EXPECT_EQ(a[rank - 1], sorted[rank - 1]);
}

}  // namespace
}  // namespace prism

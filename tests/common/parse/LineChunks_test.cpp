#include "parse/LineChunks.h"

#include <gtest/gtest.h>

#include <string>

namespace prism {
namespace {

std::string joined(const std::vector<std::string_view>& pieces) {
  std::string text;
  for (std::string_view piece : pieces) text += piece;
  return text;
}

TEST(LineChunks, PiecesEndAtLineEndsAndTogetherAreTheText) {
  const std::string text = "ab\ncd\r\nef\rgh\r\n\nlast";
  for (size_t size = 1; size <= text.size() + 1; ++size) {
    const std::vector<std::string_view> pieces = splitAtLineEnds(text, size);
    EXPECT_EQ(joined(pieces), text) << size;
    for (size_t i = 0; i + 1 < pieces.size(); ++i) {
      const char last = pieces[i].back();
      EXPECT_TRUE(last == '\n' || last == '\r') << "piece " << i << " of size " << size;
      // A \r\n pair is never split.
      EXPECT_FALSE(last == '\r' && pieces[i + 1].front() == '\n') << size;
    }
  }
  // Whole lines: a piece ends at the first line end at or after its size.
  EXPECT_EQ(splitAtLineEnds(text, 4),
            (std::vector<std::string_view>{"ab\ncd\r\n", "ef\rgh\r\n", "\nlast"}));
  EXPECT_EQ(splitAtLineEnds(text, 100), (std::vector<std::string_view>{text}));
  EXPECT_TRUE(splitAtLineEnds("", 4).empty());
}

TEST(LineChunks, NextLineStartTakesCrLfAsOneEnd) {
  const std::string text = "a\r\nb\rc\nd";
  const char* end = text.data() + text.size();
  EXPECT_EQ(nextLineStart(text.data(), end), text.data() + 3);
  EXPECT_EQ(nextLineStart(text.data() + 3, end), text.data() + 5);
  EXPECT_EQ(nextLineStart(text.data() + 5, end), text.data() + 7);
  EXPECT_EQ(nextLineStart(text.data() + 7, end), end);
}

}  // namespace
}  // namespace prism

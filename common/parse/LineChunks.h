// Text cut into pieces at line ends, so that the pieces can be parsed on several threads and
// their results joined in order.
#pragma once

#include <string_view>
#include <vector>

namespace prism {

// Where the line that starts at `from` ends, its end included: after the next \n, \r\n or lone
// \r (the line ends tinyobjloader and the OBJ reader count), or at the end of the text.
inline const char* nextLineStart(const char* from, const char* end) {
  while (from < end && *from != '\n' && *from != '\r') ++from;
  if (from == end) return end;
  if (*from == '\r' && from + 1 < end && from[1] == '\n') return from + 2;
  return from + 1;
}

// Consecutive pieces of text, together exactly the text, each ending at a line end (the last
// at the text's end) and each about pieceBytes long (longer where a line crosses the cut).
// Empty text gives no pieces.
std::vector<std::string_view> splitAtLineEnds(std::string_view text, size_t pieceBytes);

}  // namespace prism

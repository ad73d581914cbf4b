#include "parse/LineChunks.h"

#include <algorithm>

namespace prism {

std::vector<std::string_view> splitAtLineEnds(std::string_view text, size_t pieceBytes) {
  std::vector<std::string_view> pieces;
  pieceBytes = std::max<size_t>(pieceBytes, 1);
  const char* const end = text.data() + text.size();
  const char* begin = text.data();
  while (begin < end) {
    const char* cut = begin + std::min(pieceBytes, static_cast<size_t>(end - begin));
    // A cut between \r and \n would make one line end two: the \n goes with its \r.
    if (cut < end && cut[-1] == '\r' && *cut == '\n') ++cut;
    // Finish the line the cut falls in (a cut just after a line end is already a line start).
    if (cut < end && cut[-1] != '\n' && cut[-1] != '\r') cut = nextLineStart(cut, end);
    pieces.emplace_back(begin, static_cast<size_t>(cut - begin));
    begin = cut;
  }
  return pieces;
}

}  // namespace prism

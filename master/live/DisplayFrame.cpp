#include "master/live/DisplayFrame.h"

#include "master/live/NewsBoard.h"

namespace prism {

void DisplayFrame::apply(const DisplayNews& news) {
  writePatch(bytes_, width_, height_, news);
  state_.copyStateFrom(news);
}

}  // namespace prism

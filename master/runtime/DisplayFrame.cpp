#include "master/runtime/DisplayFrame.h"

#include "master/runtime/NewsBoard.h"

namespace prism {

void DisplayFrame::apply(const DisplayNews& news) {
  writePatch(bytes_, width_, height_, news);
  state_.copyStateFrom(news);
}

}  // namespace prism

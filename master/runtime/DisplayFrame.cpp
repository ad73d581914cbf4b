#include "master/runtime/DisplayFrame.h"

#include "master/runtime/NewsBoard.h"

namespace prism {

void DisplayFrame::apply(const DisplayNews& news) {
  writePatch(bytes_, width_, height_, news);
  state_.started = news.started;
  state_.pass = news.pass;
  state_.tilesDone = news.tilesDone;
  state_.completedPass = news.completedPass;
  state_.fullPassesDone = news.fullPassesDone;
  state_.staleTiles = news.staleTiles;
  state_.inFlight = news.inFlight;
}

}  // namespace prism

#include "master/live/LiveFeed.h"

namespace prism {

DisplayPass displayPass(const PassInfo& pass) {
  DisplayPass d;
  d.frame = pass.frame;
  d.viewId = pass.viewId;
  d.viewTag = pass.viewTag;
  d.pass = pass.pass;
  d.scale = pass.scale;
  d.firstOfView = pass.firstOfView;
  if (pass.view) {
    d.camera = pass.view->camera;
    d.samplesPerPixel = pass.view->samplesPerPixel;
  }
  if (pass.light) {
    d.caustics = pass.light->source == CausticSource::PhotonMap    ? CausticMethod::PhotonMap
                 : pass.light->source == CausticSource::CausticMap ? CausticMethod::CausticMap
                                                                   : CausticMethod::None;
  }
  d.tiles = static_cast<uint32_t>(pass.tiles.size());
  return d;
}

LiveFeed::LiveFeed(int width, int height, float exposure)
    : frame_(width, height), encoder_(exposure), board_(width, height) {}

bool LiveFeed::noteLocked(bool urgent) {
  const bool wake = !waiting_ || (urgent && !waitingUrgent_);
  waiting_ = true;
  waitingUrgent_ = waitingUrgent_ || urgent;
  return wake;
}

void LiveFeed::passStarted(const PassInfo& pass) {
  bool wake;
  {
    std::lock_guard lock(mutex_);
    if (!started_ || pass.viewId != frame_.pass().viewId) fullPassesDone_ = 0;
    started_ = true;
    frame_.beginPass(pass);
    wake = noteLocked(true);
  }
  wakeIf(wake, true);
}

void LiveFeed::tileAssigned(uint32_t frame, uint32_t tile, int rank) {
  bool wake = false;
  {
    std::lock_guard lock(mutex_);
    if (frame_.assign(frame, tile, rank)) wake = noteLocked(false);
  }
  wakeIf(wake, false);
}

void LiveFeed::tileFinished(uint32_t frame, std::shared_ptr<const TileResult> tile, int) {
  bool wake = false;
  {
    std::lock_guard lock(mutex_);
    if (frame_.addTile(frame, *tile)) wake = noteLocked(false);
  }
  wakeIf(wake, false);
}

void LiveFeed::passFinished(uint32_t frame, double) {
  bool wake = false;
  {
    std::lock_guard lock(mutex_);
    if (frame == frame_.frame()) {
      const DisplayPass pass = displayPass(frame_.pass());
      if (pass.pass >= 1) ++fullPassesDone_;
      board_.passCompleted(pass);
      wake = noteLocked(true);
    }
  }
  wakeIf(wake, true);
}

void LiveFeed::statsUpdated(const LiveStats& stats) {
  bool wake;
  {
    std::lock_guard lock(mutex_);
    board_.setStats(stats);
    wake = noteLocked(false);
  }
  wakeIf(wake, false);
}

void LiveFeed::encodeDirtyLocked() {
  const TileRect r = frame_.takeDirty();
  if (r.width <= 0 || r.height <= 0) return;
  const ImageRgb& image = frame_.image();
  std::vector<uint8_t>& bytes = board_.bytes();
  for (int y = r.y; y < r.y + r.height; ++y) {
    uint8_t* out = &bytes[(static_cast<size_t>(y) * image.width + r.x) * 3];
    const Color* in = &image.at(r.x, y);
    for (int x = 0; x < r.width; ++x) {
      out[3 * x + 0] = encoder_(in[x].r);
      out[3 * x + 1] = encoder_(in[x].g);
      out[3 * x + 2] = encoder_(in[x].b);
    }
  }
  board_.markChanged(r);
}

DisplayNews LiveFeed::take(bool whole) {
  std::lock_guard lock(mutex_);
  encodeDirtyLocked();
  DisplayNews state;
  state.started = started_;
  if (started_) {
    state.pass = displayPass(frame_.pass());
    state.tilesDone = static_cast<uint32_t>(frame_.tilesDone());
    state.completedPass = frame_.completedPass();
    state.fullPassesDone = fullPassesDone_;
    state.staleTiles = frame_.staleTiles();
    for (const FrameAccumulator::InFlight& t : frame_.inFlight()) {
      state.inFlight.push_back({t.rect, t.rank});
    }
  }
  board_.setState(state);
  waiting_ = waitingUrgent_ = false;
  return board_.take(whole);
}

ImageRgb LiveFeed::image() {
  std::lock_guard lock(mutex_);
  return frame_.image();
}

}  // namespace prism

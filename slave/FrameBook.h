// The frames a slave is working on, by id (ids only grow): each one's view, the jobs of it
// received and the tiles it still holds. A View (the viewer) starts a frame and names the oldest
// one still running (the viewer pipelines its frames); a job of a later frame without a View
// (the passes of `prism render`) ends every earlier one. Work of a frame that has ended is
// stale: its queued tiles are dropped, the ones being rendered stop after their row, and their
// results are not sent. The counts are what the heartbeat reports (progress()).
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <vector>

#include "render/RenderView.h"
#include "wire/Messages.h"

namespace prism {

struct FrameWork {
  std::shared_ptr<const RenderView> view;  // the viewer's; `prism render` uses the scene's
  uint64_t received = 0;                   // jobs of this frame
  std::set<uint32_t> held;                 // its tiles received, not yet returned
  // Set when the frame ends: its tiles being rendered stop after their row.
  std::shared_ptr<std::atomic<bool>> ended = std::make_shared<std::atomic<bool>>(false);
};

class FrameBook {
 public:
  // A View: frame `frame` starts afresh with `view`, every frame before liveFrom ends.
  FrameWork& startView(uint32_t frame, uint32_t liveFrom, RenderView view);
  // The frame a tile job names, started if it is new (ending every earlier one); null when it
  // has ended already.
  FrameWork* frameOfJob(uint32_t frame);
  // A finished tile leaves its frame's held tiles; false when the frame has ended (the result
  // is stale: not to be sent).
  bool finish(uint32_t frame, uint32_t tile);
  // The heartbeat's news: one Progress per running frame, or one of frame 0 (nothing yet).
  std::vector<wire::ProgressMessage> progress() const;

 private:
  using Frames = std::map<uint32_t, FrameWork>;
  // Ends the frames [first, last): the ones being rendered stop (a camera move must not wait
  // for the tiles of a view nobody sees any more).
  void end(Frames::iterator first, Frames::iterator last);

  Frames frames_;
};

}  // namespace prism

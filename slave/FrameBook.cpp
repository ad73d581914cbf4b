#include "slave/FrameBook.h"

#include <utility>

namespace prism {

FrameWork& FrameBook::startView(uint32_t frame, uint32_t liveFrom, RenderView view) {
  end(frames_.begin(), frames_.lower_bound(liveFrom));
  FrameWork& work = frames_[frame];
  work = FrameWork{};
  work.view = std::make_shared<const RenderView>(std::move(view));
  return work;
}

FrameWork* FrameBook::frameOfJob(uint32_t frame) {
  const auto found = frames_.find(frame);
  if (found != frames_.end()) return &found->second;
  if (!frames_.empty() && frame < frames_.rbegin()->first) return nullptr;  // ended already
  end(frames_.begin(), frames_.end());  // a later frame of `prism render`
  return &frames_.emplace(frame, FrameWork{}).first->second;
}

bool FrameBook::finish(uint32_t frame, uint32_t tile) {
  const auto work = frames_.find(frame);
  if (work == frames_.end()) return false;  // finished after the viewer moved on
  work->second.held.erase(tile);
  return true;
}

std::vector<wire::ProgressMessage> FrameBook::progress() const {
  std::vector<wire::ProgressMessage> progress;
  for (const auto& [id, work] : frames_) {
    progress.push_back({id, work.received, {work.held.begin(), work.held.end()}});
  }
  if (progress.empty()) progress.push_back({});
  return progress;
}

void FrameBook::end(Frames::iterator first, Frames::iterator last) {
  for (auto f = first; f != last; ++f) *f->second.ended = true;
  frames_.erase(first, last);
}

}  // namespace prism

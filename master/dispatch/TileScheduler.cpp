#include "master/dispatch/TileScheduler.h"

#include <algorithm>
#include <stdexcept>

namespace prism {

TileScheduler::TileScheduler(size_t tileCount, int workerCount, Schedule schedule,
                             double leaseSeconds, const std::vector<bool>& active)
    : schedule_(schedule),
      leaseSeconds_(leaseSeconds),
      workers_(static_cast<size_t>(std::max(workerCount, 1))),
      done_(tileCount, false),
      issued_(tileCount, false) {
  std::vector<size_t> taking;  // the workers that take part, in rank order
  for (size_t w = 0; w < workers_.size(); ++w) {
    workers_[w].idle = w < active.size() && !active[w];
    if (!workers_[w].idle) taking.push_back(w);
  }
  if (taking.empty()) throw std::invalid_argument("TileScheduler: no active worker");
  for (uint32_t tile = 0; tile < tileCount; ++tile) {
    if (schedule_ == Schedule::Static) {
      workers_[taking[tile % taking.size()]].own.push_back(tile);
    } else {
      shared_.push_back(tile);
    }
  }
}

void TileScheduler::exemptFromLeases(int worker) {
  workers_[worker].exempt = true;
}

std::optional<uint32_t> TileScheduler::next(int worker, double now) {
  Worker& w = workers_[worker];
  if (w.retired || w.idle) return std::nullopt;
  // A worker's own tiles first (static), then the shared queue. Skip tiles finished meanwhile
  // (a reclaimed tile whose late result arrived).
  for (std::deque<uint32_t>* queue : {&w.own, &shared_}) {
    while (!queue->empty()) {
      const uint32_t tile = queue->front();
      queue->pop_front();
      if (done_[tile]) continue;
      if (w.leased.empty()) w.lastProgress = now;  // the lease clock starts with the first lease
      w.leased.push_back(tile);
      w.leasedSeq.push_back(w.sent++);
      issued_[tile] = true;
      return tile;
    }
  }
  return std::nullopt;
}

bool TileScheduler::complete(uint32_t tile, int worker, double now) {
  if (tile >= done_.size() || worker < 0 || static_cast<size_t>(worker) >= workers_.size()) {
    return false;
  }
  Worker& w = workers_[worker];
  w.lastProgress = now;
  for (size_t i = 0; i < w.leased.size(); ++i) {
    if (w.leased[i] == tile) {
      w.leased.erase(w.leased.begin() + static_cast<std::ptrdiff_t>(i));
      w.leasedSeq.erase(w.leasedSeq.begin() + static_cast<std::ptrdiff_t>(i));
      break;
    }
  }
  if (!issued_[tile] || done_[tile]) return false;
  done_[tile] = true;
  ++doneCount_;
  return true;
}

void TileScheduler::retire(Worker& w) {
  w.retired = true;
  // Its tiles go to the front so the frame does not wait for them at the end.
  for (auto it = w.leased.rbegin(); it != w.leased.rend(); ++it) {
    if (!done_[*it]) {
      shared_.push_front(*it);
      ++reissued_;
    }
  }
  w.leased.clear();
  w.leasedSeq.clear();
  for (uint32_t tile : w.own) shared_.push_back(tile);
  w.own.clear();
}

size_t TileScheduler::reconcile(int worker, uint64_t jobsReceived,
                                const std::vector<uint32_t>& heldTiles) {
  Worker& w = workers_[worker];
  size_t lost = 0;
  for (size_t i = 0; i < w.leased.size();) {
    const uint32_t tile = w.leased[i];
    const bool received = w.leasedSeq[i] < jobsReceived;
    if (received && std::find(heldTiles.begin(), heldTiles.end(), tile) == heldTiles.end()) {
      w.leased.erase(w.leased.begin() + static_cast<std::ptrdiff_t>(i));
      w.leasedSeq.erase(w.leasedSeq.begin() + static_cast<std::ptrdiff_t>(i));
      if (!done_[tile]) {
        shared_.push_front(tile);
        ++reissued_;
        ++lost;
      }
      continue;
    }
    ++i;
  }
  return lost;
}

std::vector<int> TileScheduler::reclaimExpired(double now) {
  std::vector<int> expired;
  for (size_t i = 0; i < workers_.size(); ++i) {
    Worker& w = workers_[i];
    if (w.exempt || w.retired || w.leased.empty()) continue;
    if (now - w.lastProgress > leaseSeconds_) {
      retire(w);
      expired.push_back(static_cast<int>(i));
    }
  }
  return expired;
}

}  // namespace prism

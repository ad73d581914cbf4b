// The dispatcher's record of the shares being done (WorkDispatcher::runShares): what they are,
// who holds each (a TileScheduler over the shares, each owned by its rank; only rank 0 takes a
// re-issued one, as a slave works on one share at a time), and rank 0's share in progress.
// Internal to master/dispatch/WorkDispatcher*.cpp.
#pragma once

#include <future>
#include <optional>
#include <vector>

#include "master/dispatch/ShareWork.h"
#include "master/dispatch/TileScheduler.h"
#include "master/dispatch/WorkDispatcher.h"

namespace prism {

struct WorkDispatcher::ShareBatch {
  uint32_t pass = 0;
  std::vector<ShareRange> shares;
  ShareWork& work;
  TileScheduler scheduler;
  std::future<void> local;  // rank 0's share in progress, if any
  std::optional<uint32_t> localShare;

  ShareBatch(uint32_t p, std::vector<ShareRange> s, ShareWork& w, int ranks, double leaseSeconds)
      : pass(p),
        shares(std::move(s)),
        work(w),
        scheduler(shares.size(), ranks, Schedule::Static, leaseSeconds, owners(shares, ranks)) {
    scheduler.exemptFromLeases(0);
  }

  // The share planned for `rank` (its answer is accepted if that share is not done yet, even
  // once re-issued), if any.
  std::optional<size_t> ownedBy(int rank) const {
    for (size_t s = 0; s < shares.size(); ++s) {
      if (shares[s].rank == rank) return s;
    }
    return std::nullopt;
  }

 private:
  // The static schedule gives share i to the i-th active rank: the ranks that own one.
  static std::vector<bool> owners(const std::vector<ShareRange>& shares, int ranks) {
    std::vector<bool> active(static_cast<size_t>(ranks), false);
    for (const ShareRange& s : shares) active[static_cast<size_t>(s.rank)] = true;
    return active;
  }
};

}  // namespace prism

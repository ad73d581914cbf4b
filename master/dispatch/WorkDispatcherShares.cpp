// WorkDispatcher::runShares: a photon pass's shares on the run's one dispatcher, leased,
// re-issued and accepted once like tiles (master/dispatch/ShareWork.h).
#include <chrono>

#include "master/dispatch/ShareBatch.h"
#include "master/dispatch/WorkDispatcher.h"

namespace prism {

void WorkDispatcher::sendShares(ShareBatch& batch) {
  for (int r = 1; r < link_.ranks(); ++r) {
    std::optional<uint32_t> own;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      own = batch.scheduler.next(r, now());        // none for a rank without a share
      if (own && batch.shares[*own].count == 0) {  // nothing to ask for: done at once
        batch.scheduler.complete(*own, r, now());
        own.reset();
      }
    }
    // A refused send retires the rank: its share goes back, for rank 0.
    if (own && !link_.send(r, batch.work.request(batch.pass, batch.shares[*own]))) retireRank(r);
  }
}

void WorkDispatcher::cancelShares(ShareBatch& batch) {
  for (int r = 1; r < link_.ranks(); ++r) {
    bool holds = false;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      holds = batch.scheduler.outstanding(r) > 0;
    }
    if (holds) link_.send(r, wire::encode(wire::PhotonCancelMessage{batch.pass}));
  }
  if (batch.local.valid()) batch.local.wait();  // rank 0's work watches the cancel too
}

bool WorkDispatcher::runShares(uint32_t pass, const std::vector<ShareRange>& shares,
                               ShareWork& work, const std::atomic<bool>* cancel) {
  runOpening(false);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    shares_ =
        std::make_unique<ShareBatch>(pass, shares, work, link_.ranks(), options_.leaseSeconds);
    for (int r = 1; r < link_.ranks(); ++r) {
      if (link_.retired(r)) shares_->scheduler.retire(r);
    }
  }
  ShareBatch& batch = *shares_;
  struct Finish {  // the batch ends however runShares leaves; late answers are then stale
    WorkDispatcher& d;
    ~Finish() {
      const std::lock_guard<std::mutex> lock(d.mutex_);
      d.shares_.reset();
    }
  } finish{*this};
  sendShares(batch);
  for (;;) {
    if (cancel && cancel->load()) {
      cancelShares(batch);
      return false;
    }
    if (batch.local.valid() &&
        batch.local.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      batch.local.get();  // rethrows what went wrong there
      const uint32_t s = *batch.localShare;
      batch.localShare.reset();
      bool first = false;
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        first = batch.scheduler.complete(s, 0, now());
      }
      if (first) work.acceptLocal(s);
    }
    std::optional<uint32_t> next;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (batch.scheduler.finished()) return true;
      // A slave that has said Ready heartbeats: its silence retires it, not its share's length.
      for (int r = 1; r < link_.ranks(); ++r) {
        if (link_.ready(r)) batch.scheduler.exemptFromLeases(r);
      }
      // Rank 0's own share first, then any re-issued to it, one at a time.
      if (!batch.local.valid()) next = batch.scheduler.next(0, now());
    }
    if (next) {
      batch.localShare = *next;
      const ShareRange range = batch.shares[*next];
      batch.local = std::async(std::launch::async, [this, &work, s = *next, range] {
        work.doHere(s, range);
        link_.wake();  // ends the wait for the slaves' answers
      });
      continue;
    }
    if (!link_.hasSlaves()) {
      if (batch.local.valid()) batch.local.wait();
      continue;
    }
    service(0.1);  // answers, heartbeats, tiles; silent slaves and expired leases retired
  }
}

void WorkDispatcher::routeShare(const SlaveMessage& incoming) {
  ShareBatch* batch = shares_.get();
  if (!batch || incoming.message.type != batch->work.answerType()) return;  // late: pass done
  std::optional<size_t> s;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    s = batch->ownedBy(incoming.source);
  }
  if (!s) return;
  if (!batch->work.readAnswer(batch->pass, batch->shares[*s], incoming.message)) return;
  bool first = false;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    first = batch->scheduler.complete(static_cast<uint32_t>(*s), incoming.source, now());
  }
  if (first) batch->work.acceptAnswer(*s, incoming.source);
}

}  // namespace prism

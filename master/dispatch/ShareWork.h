// The shares of a photon pass's work, handed out by the run's dispatcher like tiles
// (master/dispatch/WorkDispatcher.h, runShares): one share per live rank, sized by its threads;
// each leased to its rank; a slave's share re-issued to rank 0 when the slave goes silent, is
// known gone, or is still building its scene past the lease; and each accepted once, whoever
// answers first. What a share is (photon indices to trace, or positions of a photon map's
// spatial order whose radii to find: master/frame/PhotonPass.cpp) is a ShareWork.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "wire/Messages.h"

namespace prism {

// Indices [first, first + count) of what a pass splits, planned for `rank`.
struct ShareRange {
  int rank = 0;
  uint64_t first = 0;
  uint64_t count = 0;
};

class ShareWork {
 public:
  virtual ~ShareWork() = default;
  // The message type of a slave's answer (PhotonShare, PhotonRadiiShare).
  virtual wire::MessageType answerType() const = 0;
  // The message that asks a slave for its share of pass `pass`.
  virtual std::vector<uint8_t> request(uint32_t pass, const ShareRange& share) const = 0;
  // A slave's answer, decoded: whether it answers `share` of pass `pass` (else it is late, from
  // a pass or share done without it). An answer kept is taken by acceptAnswer next.
  virtual bool readAnswer(uint32_t pass, const ShareRange& share, const wire::Message& answer) = 0;
  // The answer readAnswer kept becomes share s's result (the first answer for s only).
  virtual void acceptAnswer(size_t s, int rank) = 0;
  // Rank 0 works out share s itself, on a thread of its own (its own threads inside); the
  // result waits for acceptLocal. One at a time.
  virtual void doHere(size_t s, const ShareRange& share) = 0;
  // What doHere found becomes share s's result (unless a slave's answer came first).
  virtual void acceptLocal(size_t s) = 0;
};

}  // namespace prism

#include "master/runtime/PhotonPass.h"

#include <algorithm>
#include <future>
#include <optional>
#include <stdexcept>
#include <string>

#include "caustics/PhotonRadii.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {
namespace {

// One rank's part of a pass's work: photon indices to trace, or positions of the map's spatial
// order whose radii to find.
struct Share {
  int rank = 0;
  uint64_t first = 0, count = 0;
  bool done = false;
  int doneBy = 0;  // the rank that did it: its own, or 0 for a slave's share done there
};

// Contiguous index ranges in rank order, sized by each live rank's threads (rank 0's own count
// stands in for slaves whose Ready has not arrived yet).
std::vector<Share> planShares(uint64_t total, int localThreads, const SlaveLink& link) {
  std::vector<int> weights;
  std::vector<int> members;
  for (int r = 0; r < link.ranks(); ++r) {
    if (r > 0 && link.retired(r)) continue;
    members.push_back(r);
    const int threads = link.rank(r).threads;
    weights.push_back(r == 0 || threads <= 0 ? localThreads : threads);
  }
  uint64_t weightSum = 0;
  for (int w : weights) weightSum += static_cast<uint64_t>(w);
  std::vector<Share> shares;
  uint64_t first = 0;
  for (size_t i = 0; i < members.size(); ++i) {
    const uint64_t end = i + 1 == members.size()
                             ? total
                             : first + total * static_cast<uint64_t>(weights[i]) / weightSum;
    shares.push_back({members[i], first, end - first, false, 0});
    first = end;
  }
  return shares;
}

// Sends a message to every live slave; returns the bytes that went (a refusal retires the rank).
size_t sendToEverySlave(SlaveLink& link, const std::vector<uint8_t>& bytes) {
  size_t sent = 0;
  for (int r = 1; r < link.ranks(); ++r) {
    if (link.send(r, bytes)) sent += bytes.size();
  }
  return sent;
}

// The share a slave's message answers: its own, not yet done.
std::optional<size_t> awaitedShare(const std::vector<Share>& shares, int rank) {
  for (size_t s = 0; s < shares.size(); ++s) {
    if (shares[s].rank == rank && !shares[s].done) return s;
  }
  return std::nullopt;
}

// Waits until every share is done: rank 0's own (shares[0]) by `local`, already running on other
// threads (it wakes the link when done); a live slave's by its message, which accept(message)
// takes (marking the share done, by its rank); and one of a slave that went silent, or is still
// building its scene after the lease, by doHere(share index) on this thread once rank 0's own is
// done. Empty shares need nothing. Once *cancel is set, the slaves still working on pass `pass`
// are told to stop (PhotonCancel: their threads are wanted for the next frame's tiles, and they
// send nothing for it); then this waits for rank 0's own work (it watches cancel too) and returns
// false.
template <typename Accept, typename DoHere>
bool collectShares(std::vector<Share>& shares, uint32_t pass, SlaveLink& link,
                   std::future<void>& local, const std::atomic<bool>* cancel, Accept accept,
                   DoHere doHere) {
  const auto start = SteadyClock::now();
  const double leaseSeconds = link.options().leaseSeconds;
  for (Share& s : shares) s.done = s.rank != 0 && s.count == 0;
  for (;;) {
    if (cancel && cancel->load()) {
      for (const Share& s : shares) {
        if (s.rank != 0 && !s.done)
          link.send(s.rank, wire::encode(wire::PhotonCancelMessage{pass}));
      }
      local.wait();
      return false;
    }
    if (!shares[0].done && local.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      local.get();  // rethrows what went wrong there
      shares[0].done = true;
    }
    bool waiting = false;
    for (size_t s = 1; s < shares.size(); ++s) {
      Share& share = shares[s];
      if (share.done) continue;
      waiting = true;
      const bool lost = link.retired(share.rank) ||
                        (!link.ready(share.rank) && secondsSince(start) > leaseSeconds);
      if (!lost || !shares[0].done) continue;
      link.retire(share.rank);
      doHere(s);
      share.done = true;
      share.doneBy = 0;
    }
    if (!shares[0].done) waiting = true;
    if (!waiting) return true;
    if (!link.hasSlaves()) {
      local.wait();
      continue;
    }
    const std::optional<SlaveMessage> incoming = link.receive(0.1);
    link.retireSilent();
    // Heartbeats, late tiles of a frame already finished and late shares are passed over.
    if (incoming) accept(*incoming);
  }
}

}  // namespace

std::optional<std::vector<Photon>> tracePhotonPass(const PhotonTracer& tracer, uint32_t pass,
                                                   int threads, SlaveLink& link,
                                                   PhotonPassStats& stats,
                                                   const std::atomic<bool>* cancel) {
  const auto start = SteadyClock::now();
  std::vector<Share> shares = planShares(tracer.photonsPerPass(), threads, link);
  stats.photonsByRank.assign(static_cast<size_t>(link.ranks()), 0);
  for (const Share& share : shares) {
    if (share.rank == 0 || share.count == 0) continue;
    // A refused send retires the rank: its share is traced here.
    link.send(share.rank, wire::encode(wire::PhotonJobMessage{pass, share.first, share.count,
                                                              tracer.photonsPerPass()}));
  }
  std::vector<std::vector<Photon>> photons(shares.size());
  std::vector<PhotonTraceStats> traced(shares.size());
  const auto traceHere = [&](size_t s) {
    photons[s] =
        tracePhotons(tracer, pass, shares[s].first, shares[s].count, threads, &traced[s], cancel);
  };
  // Rank 0 traces its share on worker threads; this thread keeps talking to the slaves.
  std::future<void> local = std::async(std::launch::async, [&] {
    traceHere(0);
    link.wake();  // ends the wait for the slaves' shares
  });
  const auto accept = [&](const SlaveMessage& incoming) {
    if (incoming.message.type != wire::MessageType::PhotonShare) return;
    wire::PhotonShareMessage share = wire::decode<wire::PhotonShareMessage>(incoming.message);
    const std::optional<size_t> s = awaitedShare(shares, incoming.source);
    if (share.pass != pass || !s || share.first != shares[*s].first ||
        share.count != shares[*s].count) {
      return;  // late, from a pass or share already done without it
    }
    photons[*s] = std::move(share.photons);
    traced[*s] = share.stats;
    shares[*s].done = true;
    shares[*s].doneBy = incoming.source;
  };
  if (!collectShares(shares, pass, link, local, cancel, accept, traceHere)) return std::nullopt;
  stats.traceSeconds = secondsSince(start);
  for (size_t s = 0; s < shares.size(); ++s) {
    stats.trace += traced[s];
    stats.photonsByRank[static_cast<size_t>(shares[s].doneBy)] += shares[s].count;
  }

  size_t total = 0;
  for (const std::vector<Photon>& p : photons) total += p.size();
  std::vector<Photon> all;
  all.reserve(total);
  for (const std::vector<Photon>& p : photons) all.insert(all.end(), p.begin(), p.end());
  return all;
}

std::shared_ptr<const PhotonGather> gatherFromPhotons(std::vector<Photon> photonList, uint32_t pass,
                                                      const PhotonGatherSettings& gather,
                                                      int threads, SlaveLink& link,
                                                      PhotonPassStats& stats, bool keep,
                                                      const std::atomic<bool>* cancel) {
  const auto cancelled = [cancel] { return cancel && cancel->load(); };
  if (cancelled()) return nullptr;  // before anything is sent: the slaves keep what they had
  // Sent before rank 0 builds its kd-tree: the slaves build theirs meanwhile.
  if (link.hasSlaves()) {
    const auto sendStart = SteadyClock::now();
    stats.sentBytes +=
        sendToEverySlave(link, wire::encodePhotonMap(pass, gather, photonList, keep));
    stats.distributeSeconds = secondsSince(sendStart);
  }
  const auto buildStart = SteadyClock::now();
  auto map = std::make_shared<const PhotonMap>(std::move(photonList));
  stats.buildSeconds = secondsSince(buildStart);
  stats.mapBytes = map->bytes();
  if (cancelled()) return nullptr;
  const auto start = SteadyClock::now();
  if (!PhotonGather::needsRadii(gather, map->size())) {
    return std::make_shared<const PhotonGather>(std::move(map), gather);
  }
  // Shares of the spatial order, in whole chunks (each chunk is placed on its own, so every
  // radius is the one a single rank would find).
  const uint64_t photons = map->size();
  std::vector<Share> shares =
      planShares((photons + kPhotonRadiiChunk - 1) / kPhotonRadiiChunk, threads, link);
  for (Share& s : shares) {
    const uint64_t end = std::min(photons, (s.first + s.count) * kPhotonRadiiChunk);
    s.first *= kPhotonRadiiChunk;
    s.count = s.first < end ? end - s.first : 0;
    if (s.rank != 0 && s.count > 0)
      link.send(s.rank, wire::encode(wire::PhotonRadiiJobMessage{pass, s.first, s.count}));
  }
  std::vector<float> radii(map->size(), 0.0f);
  const auto findHere = [&](size_t s) {
    placePhotonRadii(*map, shares[s].first,
                     photonRadiiShare(*map, gather.k, gather.radius, gather.automaticK,
                                      shares[s].first, shares[s].count, threads, cancel),
                     radii);
  };
  std::future<void> local = std::async(std::launch::async, [&] {
    findHere(0);
    link.wake();
  });
  const auto accept = [&](const SlaveMessage& incoming) {
    if (incoming.message.type != wire::MessageType::PhotonRadiiShare) return;
    const wire::PhotonRadiiShareMessage share =
        wire::decode<wire::PhotonRadiiShareMessage>(incoming.message);
    const std::optional<size_t> s = awaitedShare(shares, incoming.source);
    if (share.pass != pass || !s || share.first != shares[*s].first ||
        share.radii.size() != shares[*s].count) {
      return;  // late, from a pass or share already done without it
    }
    placePhotonRadii(*map, share.first, share.radii, radii);
    shares[*s].done = true;
    shares[*s].doneBy = incoming.source;
  };
  if (!collectShares(shares, pass, link, local, cancel, accept, findHere)) return nullptr;
  if (cancelled()) return nullptr;  // moved while the last share came: no disc tree to build
  stats.radiiByRank.assign(static_cast<size_t>(link.ranks()), 0);
  for (const Share& s : shares) stats.radiiByRank[static_cast<size_t>(s.doneBy)] += s.count;
  if (link.hasSlaves()) sendToEverySlave(link, wire::encode(wire::PhotonRadiiMessage{pass, radii}));
  auto made =
      std::make_shared<const PhotonGather>(std::move(map), gather, std::move(radii), threads);
  stats.radiiSeconds = secondsSince(start);
  return made;
}

void sendPhotonMapAgain(uint32_t pass, uint32_t keptPass, SlaveLink& link) {
  sendToEverySlave(link, wire::encode(wire::PhotonMapAgainMessage{pass, keptPass}));
}

}  // namespace prism

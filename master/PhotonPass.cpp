#include "master/PhotonPass.h"

#include <future>
#include <stdexcept>
#include <string>

#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {
namespace {

struct Share {
  int rank = 0;
  uint64_t first = 0, count = 0;
  bool done = false;
  std::vector<Photon> photons;
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
    shares.push_back({members[i], first, end - first, false, {}});
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

}  // namespace

std::shared_ptr<const PhotonMap> tracePhotonPass(const PhotonTracer& tracer, uint32_t pass,
                                                 int threads, SlaveLink& link,
                                                 PhotonPassStats& stats,
                                                 const std::atomic<bool>* cancel) {
  const auto cancelled = [cancel] { return cancel && cancel->load(); };
  const auto start = SteadyClock::now();
  const int ranks = link.ranks();
  const double leaseSeconds = link.options().leaseSeconds;
  std::vector<Share> shares = planShares(tracer.photonsPerPass(), threads, link);
  stats.photonsByRank.assign(static_cast<size_t>(ranks), 0);

  for (Share& share : shares) {
    if (share.rank == 0 || share.count == 0) continue;
    // A refused send retires the rank: its share is traced here below.
    link.send(share.rank,
              wire::encodePhotonJob({pass, share.first, share.count, tracer.photonsPerPass()}));
  }
  // Rank 0 traces its share on worker threads; this thread keeps talking to the slaves.
  Share& local = shares.front();
  PhotonTraceStats localStats;
  auto localWork = std::async(std::launch::async, [&] {
    std::vector<Photon> photons =
        tracePhotons(tracer, pass, local.first, local.count, threads, &localStats, cancel);
    link.wake();  // ends the wait for the slaves' shares below
    return photons;
  });

  const auto shareOf = [&](int rank) -> Share* {
    for (Share& s : shares) {
      if (s.rank == rank && !s.done) return &s;
    }
    return nullptr;
  };
  bool localDone = false;
  for (;;) {
    if (cancelled()) {
      // The slaves still tracing this pass stop too (their threads are wanted for the next
      // frame's tiles) and send nothing for it.
      for (const Share& s : shares) {
        if (s.rank != 0 && !s.done && s.count > 0) {
          link.send(s.rank, wire::encodePhotonCancel({pass}));
        }
      }
      localWork.wait();  // within a chunk of photons
      return nullptr;
    }
    if (!localDone && localWork.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      local.photons = localWork.get();
      local.done = localDone = true;
      stats.trace += localStats;
      stats.photonsByRank[0] += local.count;
    }
    bool waiting = false;
    for (Share& s : shares) {
      if (s.done) continue;
      // Silent after its Ready: SlaveLink::retireSilent below; still building: the lease.
      if (s.rank != 0 &&
          (link.retired(s.rank) || (!link.ready(s.rank) && secondsSince(start) > leaseSeconds))) {
        // A silent or lost slave: trace its share here, once rank 0's own is finished.
        if (!localDone) {
          waiting = true;
          continue;
        }
        link.retire(s.rank);
        PhotonTraceStats recovered;
        s.photons = tracePhotons(tracer, pass, s.first, s.count, threads, &recovered, cancel);
        stats.trace += recovered;
        stats.photonsByRank[0] += s.count;
        s.done = true;
        continue;
      }
      waiting = true;
    }
    if (!waiting) break;
    if (!link.hasSlaves()) {
      localWork.wait();
      continue;
    }
    const std::optional<SlaveMessage> incoming = link.receive(0.1);
    link.retireSilent();
    if (!incoming) continue;
    switch (incoming->message.type) {
      case wire::MessageType::PhotonShare: {
        wire::PhotonShareMessage share = wire::decodePhotonShare(incoming->message);
        Share* s = shareOf(incoming->source);
        if (share.pass != pass || !s || share.first != s->first || share.count != s->count) {
          break;  // late, from a pass or share already done without it
        }
        s->photons = std::move(share.photons);
        s->done = true;
        stats.trace += share.stats;
        stats.photonsByRank[incoming->source] += s->count;
        break;
      }
      default:
        break;  // heartbeats, and late tiles of a frame already finished
    }
  }
  stats.traceSeconds = secondsSince(start);

  size_t total = 0;
  for (const Share& s : shares) total += s.photons.size();
  std::vector<Photon> photons;
  photons.reserve(total);
  for (Share& s : shares) photons.insert(photons.end(), s.photons.begin(), s.photons.end());
  const auto buildStart = SteadyClock::now();
  auto map = std::make_shared<const PhotonMap>(std::move(photons));
  stats.buildSeconds = secondsSince(buildStart);
  stats.mapBytes = map->bytes();
  return map;
}

void sendPhotonMap(const PhotonMap& map, uint32_t pass, const PhotonGatherSettings& gather,
                   SlaveLink& link, PhotonPassStats& stats, bool keep) {
  if (!link.hasSlaves()) return;
  const auto start = SteadyClock::now();
  stats.sentBytes +=
      sendToEverySlave(link, wire::encodePhotonMap(pass, gather, map.photons(), keep));
  stats.distributeSeconds = secondsSince(start);
}

void sendPhotonMapAgain(uint32_t pass, uint32_t keptPass, SlaveLink& link) {
  sendToEverySlave(link, wire::encodePhotonMapAgain({pass, keptPass}));
}

}  // namespace prism

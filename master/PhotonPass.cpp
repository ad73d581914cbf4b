#include "master/PhotonPass.h"

#include <future>
#include <stdexcept>
#include <string>

#include "transport/MpiSession.h"
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
std::vector<Share> planShares(uint64_t total, int localThreads, int ranks,
                              const ClusterRoster& roster) {
  std::vector<int> weights;
  std::vector<int> members;
  for (int r = 0; r < ranks; ++r) {
    if (r > 0 && roster.retired[r]) continue;
    members.push_back(r);
    weights.push_back(r == 0 || roster.threads[r] <= 0 ? localThreads : roster.threads[r]);
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

}  // namespace

std::shared_ptr<const PhotonMap> tracePhotonPass(const PhotonTracer& tracer, uint32_t pass,
                                                 int threads, MpiSession* cluster,
                                                 ClusterRoster& roster, double leaseSeconds,
                                                 PhotonPassStats& stats) {
  const auto start = SteadyClock::now();
  const int ranks = cluster ? cluster->size() : 1;
  std::vector<Share> shares = planShares(tracer.photonsPerPass(), threads, ranks, roster);
  stats.photonsByRank.assign(static_cast<size_t>(ranks), 0);

  for (Share& share : shares) {
    if (share.rank == 0 || share.count == 0) continue;
    if (!cluster->send(share.rank, wire::encodePhotonJob({pass, share.first, share.count,
                                                          tracer.photonsPerPass()}))) {
      roster.retired[share.rank] = true;  // gone: its share is traced here below
    }
  }
  // Rank 0 traces its share on worker threads; this thread keeps talking to the slaves.
  Share& local = shares.front();
  PhotonTraceStats localStats;
  auto localWork = std::async(std::launch::async, [&] {
    return tracePhotons(tracer, pass, local.first, local.count, threads, &localStats);
  });

  std::vector<SteadyClock::time_point> lastHeard(static_cast<size_t>(ranks), SteadyClock::now());
  const auto shareOf = [&](int rank) -> Share* {
    for (Share& s : shares) {
      if (s.rank == rank && !s.done) return &s;
    }
    return nullptr;
  };
  bool localDone = false;
  for (;;) {
    if (!localDone && localWork.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      local.photons = localWork.get();
      local.done = localDone = true;
      stats.trace += localStats;
      stats.photonsByRank[0] += local.count;
    }
    bool waiting = false;
    for (Share& s : shares) {
      if (s.done) continue;
      if (s.rank != 0 &&
          (roster.retired[s.rank] || secondsSince(lastHeard[s.rank]) > leaseSeconds)) {
        // A silent or lost slave: trace its share here, once rank 0's own is finished.
        if (!localDone) {
          waiting = true;
          continue;
        }
        roster.retired[s.rank] = true;
        PhotonTraceStats recovered;
        s.photons = tracePhotons(tracer, pass, s.first, s.count, threads, &recovered);
        stats.trace += recovered;
        stats.photonsByRank[0] += s.count;
        s.done = true;
        continue;
      }
      waiting = true;
    }
    if (!waiting) break;
    if (!cluster || ranks == 1) {
      localWork.wait();
      continue;
    }
    const std::optional<IncomingMessage> incoming = cluster->waitForMessage(0.002);
    if (!incoming) continue;
    lastHeard[incoming->source] = SteadyClock::now();
    const wire::Message message =
        wire::decodeMessage(incoming->bytes.data(), incoming->bytes.size());
    if (handleSlaveStatus(message, incoming->source, roster)) continue;
    switch (message.type) {
      case wire::MessageType::PhotonShare: {
        wire::PhotonShareMessage share = wire::decodePhotonShare(message);
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
                   MpiSession* cluster, ClusterRoster& roster, PhotonPassStats& stats) {
  if (!cluster || cluster->size() == 1) return;
  const auto start = SteadyClock::now();
  const std::vector<uint8_t> bytes = wire::encodePhotonMap(pass, gather, map.photons());
  for (int r = 1; r < cluster->size(); ++r) {
    if (roster.retired[r]) continue;
    if (cluster->send(r, bytes)) {
      stats.sentBytes += bytes.size();
    } else {
      roster.retired[r] = true;
    }
  }
  stats.distributeSeconds = secondsSince(start);
}

}  // namespace prism

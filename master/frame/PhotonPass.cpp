#include "master/frame/PhotonPass.h"

#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "caustics/PhotonRadii.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {
namespace {

// Contiguous index ranges in rank order, one per live rank, sized by its threads (rank 0's own
// count stands in for slaves whose Ready has not arrived yet).
std::vector<ShareRange> planShares(uint64_t total, int localThreads, const SlaveLink& link) {
  std::vector<int> weights;
  std::vector<int> members;
  for (const RankStats& r : link.roster()) {
    if (r.rank > 0 && r.retired) continue;
    members.push_back(r.rank);
    weights.push_back(r.rank == 0 || r.threads <= 0 ? localThreads : r.threads);
  }
  uint64_t weightSum = 0;
  for (int w : weights) weightSum += static_cast<uint64_t>(w);
  std::vector<ShareRange> shares;
  uint64_t first = 0;
  for (size_t i = 0; i < members.size(); ++i) {
    const uint64_t end = i + 1 == members.size()
                             ? total
                             : first + total * static_cast<uint64_t>(weights[i]) / weightSum;
    shares.push_back({members[i], first, end - first});
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

// Tracing a pass's photons: a share is a range of photon indices.
class TraceWork final : public ShareWork {
 public:
  TraceWork(const PhotonTracer& tracer, size_t shares, int threads, const std::atomic<bool>* cancel)
      : photons(shares), stats(shares), tracer_(tracer), threads_(threads), cancel_(cancel) {}

  wire::MessageType answerType() const override { return wire::MessageType::PhotonShare; }
  std::vector<uint8_t> request(uint32_t pass, const ShareRange& share) const override {
    return wire::encode(
        wire::PhotonJobMessage{pass, share.first, share.count, tracer_.photonsPerPass()});
  }
  bool readAnswer(uint32_t pass, const ShareRange& share, const wire::Message& answer) override {
    answer_ = wire::decode<wire::PhotonShareMessage>(answer);
    return answer_.pass == pass && answer_.first == share.first && answer_.count == share.count;
  }
  void acceptAnswer(size_t s, int rank) override {
    photons[s] = std::move(answer_.photons);
    stats[s] = answer_.stats;
    doneBy[s] = rank;
  }
  void doHere(size_t, const ShareRange& share) override {
    local_ = {};
    localPhotons_ =
        tracePhotons(tracer_, passIndex, share.first, share.count, threads_, &local_, cancel_);
  }
  void acceptLocal(size_t s) override {
    photons[s] = std::move(localPhotons_);
    stats[s] = local_;
    doneBy[s] = 0;
  }

  uint32_t passIndex = 0;
  std::vector<std::vector<Photon>> photons;  // by share
  std::vector<PhotonTraceStats> stats;       // by share
  std::map<size_t, int> doneBy;              // share -> the rank whose work was accepted

 private:
  const PhotonTracer& tracer_;
  int threads_;
  const std::atomic<bool>* cancel_;
  wire::PhotonShareMessage answer_;
  std::vector<Photon> localPhotons_;
  PhotonTraceStats local_;
};

// Finding a photon map's radii: a share is a range of positions of the map's spatial order, in
// whole chunks (each chunk is placed on its own, so every radius is the one a single rank would
// find).
class RadiiWork final : public ShareWork {
 public:
  RadiiWork(const PhotonMap& map, const PhotonGatherSettings& gather, int threads,
            const std::atomic<bool>* cancel)
      : radii(map.size(), 0.0f), map_(map), gather_(gather), threads_(threads), cancel_(cancel) {}

  wire::MessageType answerType() const override { return wire::MessageType::PhotonRadiiShare; }
  std::vector<uint8_t> request(uint32_t pass, const ShareRange& share) const override {
    return wire::encode(wire::PhotonRadiiJobMessage{pass, share.first, share.count});
  }
  bool readAnswer(uint32_t pass, const ShareRange& share, const wire::Message& answer) override {
    answer_ = wire::decode<wire::PhotonRadiiShareMessage>(answer);
    return answer_.pass == pass && answer_.first == share.first &&
           answer_.radii.size() == share.count;
  }
  void acceptAnswer(size_t s, int rank) override {
    placePhotonRadii(map_, answer_.first, answer_.radii, radii);
    doneBy[s] = rank;
  }
  void doHere(size_t, const ShareRange& share) override {
    localFirst_ = share.first;
    local_ = photonRadiiShare(map_, gather_.k, gather_.radius, gather_.automaticK, share.first,
                              share.count, threads_, cancel_);
  }
  void acceptLocal(size_t s) override {
    placePhotonRadii(map_, localFirst_, local_, radii);
    doneBy[s] = 0;
  }

  std::vector<float> radii;      // by photon index
  std::map<size_t, int> doneBy;  // share -> the rank whose work was accepted

 private:
  const PhotonMap& map_;
  PhotonGatherSettings gather_;
  int threads_;
  const std::atomic<bool>* cancel_;
  wire::PhotonRadiiShareMessage answer_;
  size_t localFirst_ = 0;
  std::vector<float> local_;
};

// Per rank, the indices of the shares each rank's work was accepted for.
std::vector<uint64_t> countByRank(const std::vector<ShareRange>& shares,
                                  const std::map<size_t, int>& doneBy, int ranks) {
  std::vector<uint64_t> byRank(static_cast<size_t>(ranks), 0);
  for (const auto& [s, rank] : doneBy) byRank[static_cast<size_t>(rank)] += shares[s].count;
  return byRank;
}

}  // namespace

std::optional<std::vector<Photon>> tracePhotonPass(const PhotonTracer& tracer, uint32_t pass,
                                                   int threads, WorkDispatcher& dispatcher,
                                                   PhotonPassStats& stats,
                                                   const std::atomic<bool>* cancel) {
  const auto start = SteadyClock::now();
  SlaveLink& link = dispatcher.link();
  const std::vector<ShareRange> shares = planShares(tracer.photonsPerPass(), threads, link);
  TraceWork work(tracer, shares.size(), threads, cancel);
  work.passIndex = pass;
  if (!dispatcher.runShares(pass, shares, work, cancel)) return std::nullopt;
  stats.traceSeconds = secondsSince(start);
  for (const PhotonTraceStats& s : work.stats) stats.trace += s;
  stats.photonsByRank = countByRank(shares, work.doneBy, link.ranks());
  size_t total = 0;
  for (const std::vector<Photon>& p : work.photons) total += p.size();
  std::vector<Photon> all;
  all.reserve(total);
  for (const std::vector<Photon>& p : work.photons) all.insert(all.end(), p.begin(), p.end());
  return all;
}

std::shared_ptr<const PhotonGather> gatherFromPhotons(std::vector<Photon> photonList, uint32_t pass,
                                                      const PhotonGatherSettings& gather,
                                                      int threads, WorkDispatcher& dispatcher,
                                                      PhotonPassStats& stats, bool keep,
                                                      const std::atomic<bool>* cancel) {
  const auto cancelled = [cancel] { return cancel && cancel->load(); };
  if (cancelled()) return nullptr;  // before anything is sent: the slaves keep what they had
  SlaveLink& link = dispatcher.link();
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
  // Shares of the spatial order in whole chunks.
  const uint64_t photons = map->size();
  std::vector<ShareRange> shares =
      planShares((photons + kPhotonRadiiChunk - 1) / kPhotonRadiiChunk, threads, link);
  for (ShareRange& s : shares) {
    const uint64_t end = std::min(photons, (s.first + s.count) * kPhotonRadiiChunk);
    s.first *= kPhotonRadiiChunk;
    s.count = s.first < end ? end - s.first : 0;
  }
  RadiiWork work(*map, gather, threads, cancel);
  if (!dispatcher.runShares(pass, shares, work, cancel)) return nullptr;
  if (cancelled()) return nullptr;  // moved while the last share came: no disc tree to build
  stats.radiiByRank = countByRank(shares, work.doneBy, link.ranks());
  if (link.hasSlaves())
    sendToEverySlave(link, wire::encode(wire::PhotonRadiiMessage{pass, work.radii}));
  auto made =
      std::make_shared<const PhotonGather>(std::move(map), gather, std::move(work.radii), threads);
  stats.radiiSeconds = secondsSince(start);
  return made;
}

std::shared_ptr<const PhotonGather> runPhotonPass(const PhotonTracer& tracer, uint32_t pass,
                                                  const PhotonGatherSettings& gather, int threads,
                                                  WorkDispatcher& dispatcher,
                                                  PhotonPassStats& stats, bool keep,
                                                  const std::atomic<bool>* cancel) {
  std::optional<std::vector<Photon>> photons =
      tracePhotonPass(tracer, pass, threads, dispatcher, stats, cancel);
  if (!photons) return nullptr;
  return gatherFromPhotons(std::move(*photons), pass, gather, threads, dispatcher, stats, keep,
                           cancel);
}

PhotonPassStats& PhotonPassStats::operator+=(const PhotonPassStats& later) {
  trace += later.trace;
  traceSeconds += later.traceSeconds;
  buildSeconds += later.buildSeconds;
  distributeSeconds += later.distributeSeconds;
  radiiSeconds += later.radiiSeconds;
  mapBytes = std::max(mapBytes, later.mapBytes);
  sentBytes += later.sentBytes;
  const auto addByRank = [](std::vector<uint64_t>& total, const std::vector<uint64_t>& pass) {
    if (total.size() < pass.size()) total.resize(pass.size());
    for (size_t r = 0; r < pass.size(); ++r) total[r] += pass[r];
  };
  addByRank(photonsByRank, later.photonsByRank);
  addByRank(radiiByRank, later.radiiByRank);
  return *this;
}

double PhotonPassStats::photonsPerSecond() const {
  return static_cast<double>(trace.emitted) / std::max(traceSeconds, 1e-6);
}

void sendPhotonMapAgain(uint32_t pass, uint32_t keptPass, SlaveLink& link) {
  sendToEverySlave(link, wire::encode(wire::PhotonMapAgainMessage{pass, keptPass}));
}

}  // namespace prism

#include "master/dispatch/SlaveLink.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace prism {

SlaveLink::SlaveLink(Transport* cluster, const DistributionOptions& options)
    : cluster_(cluster && cluster->size() > 1 ? cluster : nullptr),
      options_(options),
      rankCount_(cluster_ ? cluster_->size() : 1),
      ranks_(static_cast<size_t>(rankCount_)),
      ready_(ranks_.size(), false),
      lastHeard_(ranks_.size(), SteadyClock::now()),
      lastListened_(SteadyClock::now()) {
  for (size_t r = 0; r < ranks_.size(); ++r) ranks_[r].rank = static_cast<int>(r);
  ready_[0] = true;
}

RankStats SlaveLink::rank(int r) const {
  const std::lock_guard<std::mutex> lock(rosterMutex_);
  return ranks_[static_cast<size_t>(r)];
}

std::vector<RankStats> SlaveLink::roster() const {
  const std::lock_guard<std::mutex> lock(rosterMutex_);
  return ranks_;
}

bool SlaveLink::retired(int r) const {
  const std::lock_guard<std::mutex> lock(rosterMutex_);
  return ranks_[static_cast<size_t>(r)].retired;
}

bool SlaveLink::ready(int r) const {
  const std::lock_guard<std::mutex> lock(rosterMutex_);
  return ready_[static_cast<size_t>(r)];
}

std::vector<bool> SlaveLink::retiredRanks() const {
  const std::lock_guard<std::mutex> lock(rosterMutex_);
  std::vector<bool> retired;
  for (const RankStats& r : ranks_) retired.push_back(r.retired);
  return retired;
}

void SlaveLink::retire(int r) {
  const std::lock_guard<std::mutex> lock(rosterMutex_);
  if (r > 0 && r < ranks()) recordLocked(r).retired = true;
}

void SlaveLink::setLocalThreads(int threads) {
  const std::lock_guard<std::mutex> lock(rosterMutex_);
  recordLocked(0).threads = threads;
}

void SlaveLink::countDelivered(int r, const TileResult& tile) {
  const std::lock_guard<std::mutex> lock(rosterMutex_);
  RankStats& s = recordLocked(r);
  ++s.tiles;
  s.rays += tile.rays;
  s.busySeconds += tile.seconds;
}

void SlaveLink::countStale(int r) {
  const std::lock_guard<std::mutex> lock(rosterMutex_);
  ++recordLocked(r).staleTiles;
}

void SlaveLink::countLost(int r, size_t tiles) {
  const std::lock_guard<std::mutex> lock(rosterMutex_);
  recordLocked(r).lostTiles += tiles;
}

bool SlaveLink::send(int r, std::vector<uint8_t> bytes) {
  if (!cluster_ || r <= 0 || r >= ranks() || retired(r)) return false;
  if (cluster_->send(r, std::move(bytes))) return true;
  retire(r);  // the transport knows it is gone
  return false;
}

void SlaveLink::noteListening(SteadyClock::time_point now) {
  // Rank 0 was busy elsewhere: what the slaves said meanwhile is still queued, so nobody's
  // silence counts from before a heartbeat ago.
  const auto heartbeat = std::chrono::duration_cast<SteadyClock::duration>(
      std::chrono::duration<double>(kHeartbeatSeconds));
  if (now - lastListened_ > heartbeat) {
    for (auto& heard : lastHeard_) heard = std::max(heard, now - heartbeat);
  }
  lastListened_ = now;
}

std::optional<SlaveMessage> SlaveLink::receive(double timeoutSeconds) {
  if (!cluster_) return std::nullopt;
  noteListening(SteadyClock::now());
  std::optional<IncomingMessage> incoming = cluster_->waitForMessage(timeoutSeconds);
  lastListened_ = SteadyClock::now();
  if (!incoming) return std::nullopt;
  const int source = incoming->source;
  if (source <= 0 || source >= ranks()) return std::nullopt;  // not one of the slaves
  lastHeard_[static_cast<size_t>(source)] = SteadyClock::now();
  wire::Message message = wire::decodeMessage(incoming->bytes);
  switch (message.type) {
    case wire::MessageType::Ready: {
      const wire::ReadyMessage ready = wire::decode<wire::ReadyMessage>(message);
      const std::lock_guard<std::mutex> lock(rosterMutex_);
      RankStats& r = recordLocked(source);
      r.threads = ready.threads;
      r.buildSeconds = ready.buildSeconds;
      r.startSeconds = ready.startSeconds;
      r.mpiInitSeconds = ready.mpiInitSeconds;
      ready_[static_cast<size_t>(source)] = true;
      return std::nullopt;
    }
    case wire::MessageType::Error:
      throw std::runtime_error("rank " + std::to_string(source) + ": " +
                               wire::decode<wire::ErrorMessage>(message).text);
    default:
      return SlaveMessage{source, std::move(message)};
  }
}

std::vector<int> SlaveLink::retireSilent() {
  std::vector<int> silent;
  if (!cluster_) return silent;
  const auto now = SteadyClock::now();
  noteListening(now);
  const std::lock_guard<std::mutex> lock(rosterMutex_);
  for (int r = 1; r < ranks(); ++r) {
    RankStats& record = recordLocked(r);
    if (record.retired || !ready_[static_cast<size_t>(r)]) continue;
    const double quiet =
        std::chrono::duration<double>(now - lastHeard_[static_cast<size_t>(r)]).count();
    if (quiet > options_.heartbeatTimeoutSeconds) {
      record.retired = true;
      silent.push_back(r);
    }
  }
  return silent;
}

}  // namespace prism

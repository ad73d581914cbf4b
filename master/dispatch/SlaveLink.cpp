#include "master/dispatch/SlaveLink.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "wire/GeometryCodec.h"

namespace prism {
namespace {

std::string rankName(int rank) {
  return "rank " + std::to_string(rank);
}

// A slave's message decoded to its envelope; one that only rank 0 sends ends the run.
wire::Message fromSlave(int source, const std::vector<uint8_t>& bytes) {
  wire::Message message = wire::decodeMessage(bytes);
  if (!wire::goesTo(message.type, wire::Direction::ToMaster)) {
    throw std::runtime_error(rankName(source) + " sent " + wire::messageTypeName(message.type) +
                             ", which only rank 0 sends");
  }
  return message;
}

[[noreturn]] void throwSlaveError(int source, const wire::Message& error) {
  throw std::runtime_error(rankName(source) + ": " + wire::decode<wire::ErrorMessage>(error).text);
}

}  // namespace

template <class T>
std::vector<T> firstOfEachSlave(Transport& cluster, double timeoutSeconds,
                                const std::string& silence) {
  const wire::MessageType expected = wire::MessageTraits<T>::kType;
  if (!wire::goesTo(expected, wire::Direction::ToMaster) ||
      !wire::belongsTo(expected, wire::Phase::SetUp)) {
    throw std::logic_error(std::string("no set-up step waits for ") +
                           wire::messageTypeName(expected));
  }
  std::vector<T> first(static_cast<size_t>(cluster.size()));
  std::vector<bool> heard(first.size(), false);
  int waiting = cluster.size() - 1;
  const auto start = SteadyClock::now();
  while (waiting > 0) {
    const double left = timeoutSeconds - secondsSince(start);
    std::optional<IncomingMessage> incoming =
        left > 0.0 ? cluster.waitForMessage(left) : std::nullopt;
    if (!incoming) {
      for (size_t r = 1; r < heard.size(); ++r) {
        if (!heard[r]) throw std::runtime_error(rankName(static_cast<int>(r)) + " " + silence);
      }
    }
    const int source = incoming->source;
    if (source <= 0 || source >= cluster.size() || heard[static_cast<size_t>(source)]) continue;
    const wire::Message message = fromSlave(source, incoming->bytes);
    if (message.type == wire::MessageType::Error) throwSlaveError(source, message);
    if (message.type != expected) {
      throw std::runtime_error(rankName(source) + " sent " + wire::messageTypeName(message.type) +
                               " before " + wire::messageTypeName(expected));
    }
    first[static_cast<size_t>(source)] = wire::decode<T>(message);
    heard[static_cast<size_t>(source)] = true;
    --waiting;
  }
  return first;
}

// Every message of the list, so that a new set-up message needs nothing here. The list names
// its structs as wire/Messages.h sees them, inside namespace wire.
using namespace wire;  // NOLINT(google-build-using-namespace)
#define PRISM_ROLL_CALL(name, number, Type, ...) \
  template std::vector<Type> firstOfEachSlave<Type>(Transport&, double, const std::string&);
PRISM_WIRE_MESSAGES(PRISM_ROLL_CALL)
#undef PRISM_ROLL_CALL

std::optional<int> nextShutdownAcknowledgement(Transport& cluster, double waitSeconds) {
  const std::optional<IncomingMessage> incoming = cluster.waitForMessage(waitSeconds);
  if (!incoming || incoming->source <= 0 || incoming->source >= cluster.size()) return std::nullopt;
  try {
    if (wire::decodeMessage(incoming->bytes).type != wire::MessageType::Shutdown) {
      return std::nullopt;
    }
  } catch (const wire::WireError&) {
    return std::nullopt;
  }
  return incoming->source;
}

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
  wire::Message message = fromSlave(source, incoming->bytes);
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
      throwSlaveError(source, message);
    default:
      return SlaveMessage{source, std::move(message)};
  }
}

bool SlaveLink::awaitEcho(int r, uint32_t sequence, double timeoutSeconds) {
  const auto start = SteadyClock::now();
  while (secondsSince(start) < timeoutSeconds) {
    const std::optional<SlaveMessage> incoming = receive(0.1);
    // Other than this echo: a late echo of an earlier probe, or a heartbeat.
    if (incoming && incoming->source == r && incoming->message.type == wire::MessageType::Echo &&
        wire::decode<wire::EchoMessage>(incoming->message).sequence == sequence) {
      return true;
    }
  }
  return false;
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

#include "master/LinkProbe.h"

#include <stdexcept>
#include <string>

#include "transport/MpiSession.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {
namespace {

constexpr double kEchoTimeoutSeconds = 30.0;

// Waits for the Echo of `sequence` from `rank`, handling what else arrives meanwhile.
void awaitEcho(MpiSession& session, ClusterRoster& roster, int rank, uint32_t sequence) {
  const auto start = SteadyClock::now();
  while (secondsSince(start) < kEchoTimeoutSeconds) {
    const auto incoming = session.waitForMessage(0.1);
    if (!incoming) continue;
    const wire::Message message = wire::decodeMessage(incoming->bytes);
    if (handleSlaveStatus(message, incoming->source, roster)) continue;
    // Other than our echo: a late echo of an earlier probe, or a heartbeat.
    if (message.type == wire::MessageType::Echo && incoming->source == rank &&
        wire::decodeEcho(message).sequence == sequence) {
      return;
    }
  }
  throw std::runtime_error("rank " + std::to_string(rank) + " did not echo a link probe within " +
                           std::to_string(static_cast<int>(kEchoTimeoutSeconds)) + " s");
}

}  // namespace

LinkMeasurement measureLink(MpiSession& session, ClusterRoster& roster, size_t largePayloadBytes,
                            int roundTrips) {
  const std::vector<uint8_t> small = wire::encodeEcho({0, {}});
  const std::string padding(largePayloadBytes, '\0');
  std::vector<double> smallTrips, largeTrips;
  uint32_t sequence = 0;
  for (int rank = 1; rank < session.size(); ++rank) {
    if (roster.retired[rank]) continue;
    for (int trip = 0; trip < roundTrips; ++trip) {
      for (bool large : {false, true}) {
        const auto start = SteadyClock::now();
        session.send(rank, wire::encodeEcho({++sequence, large ? padding : std::string()}));
        awaitEcho(session, roster, rank, sequence);
        (large ? largeTrips : smallTrips).push_back(secondsSince(start));
      }
    }
  }
  if (smallTrips.empty()) throw std::runtime_error("no slave to measure the link with");
  LinkMeasurement link;
  link.smallBytes = small.size();
  link.largeBytes = wire::encodeEcho({0, padding}).size();
  link.roundTrips = roundTrips;
  link.smallRoundTrip = spreadOf(smallTrips);
  link.largeRoundTrip = spreadOf(largeTrips);
  link.model.latencySeconds = link.smallRoundTrip.median / 2;
  const double extraOneWay = (link.largeRoundTrip.median - link.smallRoundTrip.median) / 2;
  if (extraOneWay > 0.0) {
    link.model.bytesPerSecond =
        static_cast<double>(link.largeBytes - link.smallBytes) / extraOneWay;
  }
  return link;
}

}  // namespace prism

#include "master/analysis/LinkProbe.h"

#include <stdexcept>
#include <string>

#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {
namespace {

constexpr double kEchoTimeoutSeconds = 30.0;

// Waits for the Echo of `sequence` from `rank`, handling what else arrives meanwhile.
void awaitEcho(SlaveLink& link, int rank, uint32_t sequence) {
  if (link.awaitEcho(rank, sequence, kEchoTimeoutSeconds)) return;
  throw std::runtime_error("rank " + std::to_string(rank) + " did not echo a link probe within " +
                           std::to_string(static_cast<int>(kEchoTimeoutSeconds)) + " s");
}

}  // namespace

LinkMeasurement measureLink(SlaveLink& link, size_t largePayloadBytes, int roundTrips) {
  const std::vector<uint8_t> small = wire::encode(wire::EchoMessage{0, {}});
  const std::string padding(largePayloadBytes, '\0');
  std::vector<double> smallTrips, largeTrips;
  uint32_t sequence = 0;
  for (int rank = 1; rank < link.ranks(); ++rank) {
    if (link.retired(rank)) continue;
    for (int trip = 0; trip < roundTrips; ++trip) {
      for (bool large : {false, true}) {
        const auto start = SteadyClock::now();
        if (!link.send(rank, wire::encode(
                                 wire::EchoMessage{++sequence, large ? padding : std::string()}))) {
          throw std::runtime_error("rank " + std::to_string(rank) + " is gone");
        }
        awaitEcho(link, rank, sequence);
        (large ? largeTrips : smallTrips).push_back(secondsSince(start));
      }
    }
  }
  if (smallTrips.empty()) throw std::runtime_error("no slave to measure the link with");
  LinkMeasurement measured;
  measured.smallBytes = small.size();
  measured.largeBytes = wire::encode(wire::EchoMessage{0, padding}).size();
  measured.roundTrips = roundTrips;
  measured.wakesOnMessage = link.transport()->wakesOnMessage();
  measured.smallRoundTrip = spreadOf(smallTrips);
  measured.largeRoundTrip = spreadOf(largeTrips);
  measured.model.latencySeconds = measured.smallRoundTrip.median / 2;
  const double extraOneWay = (measured.largeRoundTrip.median - measured.smallRoundTrip.median) / 2;
  if (extraOneWay > 0.0) {
    measured.model.bytesPerSecond =
        static_cast<double>(measured.largeBytes - measured.smallBytes) / extraOneWay;
  }
  return measured;
}

}  // namespace prism

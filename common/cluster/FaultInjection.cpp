#include "cluster/FaultInjection.h"

#include <stdexcept>

namespace prism {

FaultInjection parseFaultInjection(const std::string& text) {
  const size_t colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  FaultInjection fault;
  if (kind == "hang") {
    fault.kind = FaultInjection::Kind::Hang;
  } else if (kind == "drop") {
    fault.kind = FaultInjection::Kind::DropTiles;
  } else if (kind == "crash") {
    fault.kind = FaultInjection::Kind::Crash;
  } else if (kind == "slow") {
    fault.kind = FaultInjection::Kind::Slow;
  }
  size_t used = 0;
  int rank = -1;
  if (colon != std::string::npos) {
    try {
      rank = std::stoi(text.substr(colon + 1), &used);
    } catch (const std::exception&) {
      used = 0;
    }
  }
  if (fault.kind == FaultInjection::Kind::None || colon == std::string::npos || rank < 1 ||
      used != text.size() - colon - 1) {
    throw std::invalid_argument(
        "fault injection '" + text +
        "' must be hang:RANK, drop:RANK, crash:RANK or slow:RANK with a slave rank >= 1");
  }
  fault.rank = rank;
  return fault;
}

}  // namespace prism

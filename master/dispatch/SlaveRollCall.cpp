#include "master/dispatch/SlaveRollCall.h"

#include <optional>
#include <stdexcept>

#include "transport/Transport.h"
#include "util/Stopwatch.h"

namespace prism {

std::vector<wire::Message> firstMessageOfEachSlave(Transport& cluster, wire::MessageType expected,
                                                   double timeoutSeconds,
                                                   const std::string& silence) {
  std::vector<wire::Message> first(static_cast<size_t>(cluster.size()));
  std::vector<bool> heard(first.size(), false);
  int waiting = cluster.size() - 1;
  const auto start = SteadyClock::now();
  while (waiting > 0) {
    const double left = timeoutSeconds - secondsSince(start);
    std::optional<IncomingMessage> incoming =
        left > 0.0 ? cluster.waitForMessage(left) : std::nullopt;
    if (!incoming) {
      for (size_t r = 1; r < heard.size(); ++r) {
        if (!heard[r]) throw std::runtime_error("rank " + std::to_string(r) + " " + silence);
      }
    }
    const int source = incoming->source;
    if (source <= 0 || source >= cluster.size() || heard[static_cast<size_t>(source)]) continue;
    wire::Message message = wire::decodeMessage(incoming->bytes);
    if (message.type == wire::MessageType::Error) {
      throw std::runtime_error("rank " + std::to_string(source) + ": " +
                               wire::decode<wire::ErrorMessage>(message).text);
    }
    if (message.type != expected) {
      throw std::runtime_error("rank " + std::to_string(source) + " sent " +
                               wire::messageTypeName(message.type) + " before " +
                               wire::messageTypeName(expected));
    }
    first[static_cast<size_t>(source)] = std::move(message);
    heard[static_cast<size_t>(source)] = true;
    --waiting;
  }
  return first;
}

}  // namespace prism

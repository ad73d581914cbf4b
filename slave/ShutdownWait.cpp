#include "slave/ShutdownWait.h"

#include "transport/Transport.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {

bool awaitShutdown(Transport& transport, double timeoutSeconds) {
  const auto start = SteadyClock::now();
  while (secondsSince(start) < timeoutSeconds) {
    const auto incoming = transport.waitForMessage(0.1);
    if (!incoming) continue;
    try {
      if (wire::decodeMessage(incoming->bytes).type == wire::MessageType::Shutdown) {
        transport.send(
            0, wire::encode(wire::ShutdownMessage{}));  // acknowledged: the master may finish
        return true;
      }
    } catch (const wire::WireError&) {
    }
  }
  return false;
}

}  // namespace prism

#include "master/dispatch/SlaveShutdown.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <ostream>
#include <thread>

#include "master/dispatch/SlaveLink.h"
#include "transport/Transport.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {
int shutDownSlaves(Transport* session, int exitCode, const std::vector<bool>& silent,
                   std::ostream& err) {
  if (!session || session->size() <= 1) return exitCode;
  constexpr double kAcknowledgeSeconds = 10.0;
  constexpr double kSilentAcknowledgeSeconds = 2.0;
  std::vector<bool> gone(static_cast<size_t>(session->size()), false);
  std::vector<bool> lost(static_cast<size_t>(session->size()), false);
  int waiting = session->size() - 1;
  for (int rank = 1; rank < session->size(); ++rank) {
    if (!session->send(rank, wire::encode(wire::ShutdownMessage{}))) {
      gone[rank] = lost[rank] = true;  // the transport knows its process has ended
      --waiting;
    }
  }
  const auto start = std::chrono::steady_clock::now();
  auto onlySilentLeft = [&] {
    for (int rank = 1; rank < session->size(); ++rank) {
      if (!gone[rank] && !(rank < static_cast<int>(silent.size()) && silent[rank])) return false;
    }
    return true;
  };
  while (waiting > 0 && secondsSince(start) < kAcknowledgeSeconds &&
         !(onlySilentLeft() && secondsSince(start) > kSilentAcknowledgeSeconds)) {
    const std::optional<int> acknowledged = nextShutdownAcknowledgement(*session, 0.05);
    if (!acknowledged || gone[*acknowledged]) continue;
    gone[*acknowledged] = true;
    --waiting;
  }
  // MPI_Finalize waits for every rank, a dead one too (seen hanging under --enable-recovery):
  // with a rank lost the job ends with MPI_Abort, once the others have acknowledged.
  const bool anyLost = std::find(lost.begin(), lost.end(), true) != lost.end();
  if (waiting == 0 && !anyLost) return exitCode;
  for (int rank = 1; rank < session->size(); ++rank) {
    if (lost[rank]) {
      err << "prism: rank " << rank
          << " has ended; ending the job with MPI_Abort so that MPI_Finalize does not wait for "
             "it\n";
    } else if (!gone[rank]) {
      err << "prism: rank " << rank << " did not acknowledge the end of the job in "
          << secondsSince(start) << " s; ending the job with MPI_Abort so it does not hang\n";
    }
  }
  err.flush();
  session->abortJob(exitCode);
  return exitCode;  // not reached; GCC does not carry [[noreturn]] through a virtual call
}

void leaveEndingJob(Transport& session, int exitCode) {
  for (int rank = 1; rank < session.size(); ++rank)
    session.send(rank, wire::encode(wire::ShutdownMessage{}));
  const auto start = std::chrono::steady_clock::now();
  while (session.progressSends() > 0 && secondsSince(start) < 0.1) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  std::fflush(nullptr);
  std::_Exit(exitCode);
}

}  // namespace prism

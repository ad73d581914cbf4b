#include "master/runtime/JobInstructionSet.h"

#include <stdexcept>

#include "transport/Transport.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {
namespace {

std::string rankText(int rank, const std::string& cpu) {
  return "rank " + std::to_string(rank) + " (" + cpu + ")";
}

}  // namespace

std::string JobInstructionSet::describe() const {
  std::string text = instructionSetName(chosen);
  if (requested != InstructionSet::Auto) return text + " (--isa)";
  if (limitingRank >= 0) {
    return text + " (rank " + std::to_string(limitingRank) + " runs no more: " + limitingCpu + ")";
  }
  return text + (ranks > 1 ? " (the best every rank runs)" : " (the best this CPU runs)");
}

JobInstructionSet chooseJobInstructionSet(Transport* cluster, InstructionSet requested,
                                          double timeoutSeconds) {
  JobInstructionSet job;
  job.requested = requested;
  const InstructionSet ownBest = bestInstructionSet(runnableInstructionSets());
  job.chosen = resolveInstructionSet(requested);  // throws when rank 0 cannot run it
  if (cluster == nullptr || cluster->size() <= 1) return job;
  job.ranks = cluster->size();

  std::vector<wire::HelloMessage> hellos(static_cast<size_t>(cluster->size()));
  std::vector<bool> heard(hellos.size(), false);
  int waiting = cluster->size() - 1;
  const auto start = SteadyClock::now();
  while (waiting > 0) {
    const double left = timeoutSeconds - secondsSince(start);
    std::optional<IncomingMessage> incoming =
        left > 0.0 ? cluster->waitForMessage(left) : std::nullopt;
    if (!incoming) {
      for (size_t r = 1; r < heard.size(); ++r) {
        if (!heard[r]) {
          throw std::runtime_error("rank " + std::to_string(r) + " did not say which CPU it has");
        }
      }
    }
    const int source = incoming->source;
    if (source <= 0 || source >= cluster->size() || heard[static_cast<size_t>(source)]) continue;
    const wire::Message message = wire::decodeMessage(incoming->bytes);
    if (message.type == wire::MessageType::Error) {
      throw std::runtime_error("rank " + std::to_string(source) + ": " +
                               wire::decode<wire::ErrorMessage>(message).text);
    }
    if (message.type != wire::MessageType::Hello) {
      throw std::runtime_error("rank " + std::to_string(source) + " sent " +
                               wire::messageTypeName(message.type) + " before Hello");
    }
    hellos[static_cast<size_t>(source)] = wire::decode<wire::HelloMessage>(message);
    heard[static_cast<size_t>(source)] = true;
    --waiting;
  }

  InstructionSetMask common = runnableInstructionSets();
  for (size_t r = 1; r < hellos.size(); ++r) {
    const wire::HelloMessage& hello = hellos[r];
    if (requested != InstructionSet::Auto && !(hello.instructionSets & maskOf(requested))) {
      throw std::runtime_error(std::string("--isa ") + instructionSetName(requested) + ": " +
                               rankText(static_cast<int>(r), hello.cpu) + " runs at most " +
                               instructionSetName(bestInstructionSet(hello.instructionSets)));
    }
    common &= hello.instructionSets;
  }
  if (requested != InstructionSet::Auto) return job;
  job.chosen = bestInstructionSet(common);
  if (job.chosen != ownBest) {
    for (size_t r = 1; r < hellos.size(); ++r) {
      if (bestInstructionSet(hellos[r].instructionSets) == job.chosen) {
        job.limitingRank = static_cast<int>(r);
        job.limitingCpu = hellos[r].cpu;
        break;
      }
    }
  }
  return job;
}

}  // namespace prism

#include "master/dispatch/JobInstructionSet.h"

#include <stdexcept>

#include "master/dispatch/SlaveLink.h"
#include "transport/Transport.h"
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

  const std::vector<wire::HelloMessage> hellos = firstOfEachSlave<wire::HelloMessage>(
      *cluster, timeoutSeconds, "did not say which CPU it has");

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

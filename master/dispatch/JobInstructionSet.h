// The one instruction set a job's kernels run on every rank (util/InstructionSet.h): each
// slave's first message (Hello) says what its CPU runs, and rank 0 takes the best that every
// rank runs, or the one the command line forced if every rank runs it, before the scene is
// broadcast: the choice travels in the scene's render settings, so no rank renders a pixel with
// another set and a mixed cluster still gives the image one machine gives.
#pragma once

#include <string>

#include "util/InstructionSet.h"

namespace prism {

class Transport;

struct JobInstructionSet {
  InstructionSet chosen = InstructionSet::Baseline;
  InstructionSet requested = InstructionSet::Auto;
  // Under Auto, the lowest-ranked rank that holds the choice below rank 0's best (-1: none);
  // its CPU's name.
  int limitingRank = -1;
  std::string limitingCpu;
  int ranks = 1;  // in the job

  // "x86-64-v4 (the best every rank runs)", "x86-64-v2 (rank 2 runs no more: Intel Xeon ...)",
  // "x86-64-v3 (--isa)", one process "x86-64-v4 (the best this CPU runs)": for the run
  // summary and the speedup CSV.
  std::string describe() const;
};

// Waits for every slave's Hello (up to timeoutSeconds in all) and chooses. cluster null or of one
// rank: this process alone. Throws std::runtime_error naming the rank and its CPU when a forced
// set is beyond one, a slave sends an Error or anything else first, or one stays silent.
JobInstructionSet chooseJobInstructionSet(Transport* cluster, InstructionSet requested,
                                          double timeoutSeconds);

}  // namespace prism

// A progressive run's time budget (`--time-budget`, the scene's time_budget), read as its user
// reads it: from the command's start to the written image, set-up, direct light and the write
// included. A pass starts only if, as long as the longest pass so far, it would end with time
// left to write the image: a pass started just before the budget ran out and run to its end
// would overrun it. Pure arithmetic on times measured elsewhere, so that the rule is tested without
// a clock.
#pragma once

#include <cstddef>

namespace prism {

struct PassBudget {
  double seconds = 0.0;       // the whole run's budget; 0: none
  double writeSeconds = 0.0;  // what writing the image is expected to take
};

// The seconds writing an image of `pixels` pixels is budgeted: 0.2 s a megapixel, above the
// 0.11–0.16 s the 1024² PNG and EXR writes measured on this project's 2-core machine.
double budgetedWriteSeconds(size_t pixels);

// Whether caustic pass `pass` (1, 2, ...) starts `elapsed` seconds into the run, when the longest
// pass so far took `longestPass` seconds. Pass 1 always starts (an image needs one); a later
// one only if elapsed + longestPass + the write fits in the budget. No budget: always.
bool startsPass(const PassBudget& budget, int pass, double elapsed, double longestPass);

}  // namespace prism

#include "master/frame/PassBudget.h"

namespace prism {

double budgetedWriteSeconds(size_t pixels) {
  return 0.2e-6 * static_cast<double>(pixels);
}

bool startsPass(const PassBudget& budget, int pass, double elapsed, double longestPass) {
  if (pass <= 1 || !(budget.seconds > 0.0)) return true;
  return elapsed + longestPass + budget.writeSeconds <= budget.seconds;
}

}  // namespace prism

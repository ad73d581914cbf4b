// A memory limit spent piece by piece (the meshes of a scene, one after another): what is left
// for the next piece, with a source that says the earlier pieces were counted, so a refusal
// reads "the memory limit is 1.0 GiB (..., --memory-limit, less the meshes before this one)".
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>

#include "util/MemorySize.h"

namespace prism {

class MemoryBudget {
 public:
  // spentOn completes "less ...": e.g. "the meshes before this one".
  MemoryBudget(MemoryLimit limit, std::string spentOn)
      : limit_(std::move(limit)), spentOn_(std::move(spentOn)) {}

  void spend(uint64_t bytes) {
    spent_ = saturatingAdd(spent_, bytes);
    ++pieces_;
  }

  MemoryLimit remaining() const {
    MemoryLimit left = limit_;
    left.bytes -= std::min(left.bytes, spent_);
    if (pieces_ > 0) left.source += ", less " + spentOn_;
    return left;
  }

 private:
  MemoryLimit limit_;
  std::string spentOn_;
  uint64_t spent_ = 0;
  int pieces_ = 0;
};

}  // namespace prism

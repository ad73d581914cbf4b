// Test-only misbehaviour of one slave, to prove the master survives it (--inject-fault).
#pragma once

#include <string>

namespace prism {

struct FaultInjection {
  enum class Kind { None, Hang, DropTiles, Crash };
  Kind kind = Kind::None;
  int rank = -1;  // the slave that misbehaves

  bool appliesTo(int r) const { return kind != Kind::None && r == rank; }
};

// Parses "hang:RANK" (takes jobs, never answers), "drop:RANK" (silently drops every second
// job) or "crash:RANK" (the process dies on its first job, as if killed). Throws
// std::invalid_argument with the accepted forms.
FaultInjection parseFaultInjection(const std::string& text);

}  // namespace prism

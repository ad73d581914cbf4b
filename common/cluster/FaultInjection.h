// Test-only misbehaviour of one slave, to prove the master survives it (--inject-fault).
#pragma once

#include <string>

namespace prism {

struct FaultInjection {
  enum class Kind { None, Hang, DropTiles, Crash, Slow };
  Kind kind = Kind::None;
  int rank = -1;  // the slave that misbehaves

  bool appliesTo(int r) const { return kind != Kind::None && r == rank; }
};

// A slow rank holds each render thread this long after every tile, as a slower machine would:
// far longer than a small tile's render time, so the rank's pace is known whatever else runs.
inline constexpr double kSlowTileDelaySeconds = 0.2;

// Parses "hang:RANK" (takes jobs, never answers), "drop:RANK" (silently drops every second
// job), "crash:RANK" (the process dies on its first job, as if killed) or "slow:RANK" (every
// tile takes kSlowTileDelaySeconds longer: an uneven node). Throws std::invalid_argument with
// the accepted forms.
FaultInjection parseFaultInjection(const std::string& text);

}  // namespace prism

// Test-only misbehaviour of one slave, to prove the master survives it (--inject-fault). The
// slave's own code knows nothing of it: the rank's transport is wrapped in a decorator
// (slave/FaultInjectingTransport.h) that misbehaves as the kind below says, so every behaviour
// here is a statement about the messages that rank sends and receives.
#pragma once

#include <string>

namespace prism {

struct FaultInjection {
  // Hang: takes jobs, never answers. Incoming work (the messages whose role is Work in
  //   wire/Messages.h's list: TileJob, PhotonJob, PhotonRadiiJob) is swallowed; outgoing answers
  //   (role Answer: TileResult, Progress, PhotonShare, PhotonRadiiShare) too. Everything else
  //   (role Control: the scene, View, the photon maps, PhotonCancel, Echo, Shutdown in; Ready,
  //   Error, Echo and the Shutdown acknowledgement out) passes, so the job still ends cleanly.
  // DropTiles: every second TileJob of each frame (the 2nd, 4th, ...) is swallowed, yet counted
  //   as received in the rank's Progress of that frame, as a slave that lost it would count it:
  //   the master sees tiles received and no longer held.
  // Crash: the process ends with std::_Exit(9) when its first TileJob arrives, as if killed.
  // CrashOnPhotons: the same when its first PhotonJob arrives (a photon pass in progress).
  // Slow: a slower node. Each outgoing TileResult is held back and leaves
  //   kSlowTileDelaySeconds after the later of its hand-over and the previous result's departure
  //   on the same render thread's lane (lanes: the threads the rank's Ready announced; 1 before
  //   it), as if each render thread took that much longer per tile. A held-back tile is still
  //   held: the rank's Progress of its frame lists it. Results leave when the slave next calls
  //   the transport once they are due (its loop wakes for them).
  enum class Kind { None, Hang, DropTiles, Crash, CrashOnPhotons, Slow };
  Kind kind = Kind::None;
  int rank = -1;  // the slave that misbehaves

  bool appliesTo(int r) const { return kind != Kind::None && r == rank; }
};

// A slow rank's extra time per tile and render thread: far longer than a small tile's render
// time, so the rank's pace is known whatever else runs.
inline constexpr double kSlowTileDelaySeconds = 0.2;

// The accepted forms, for errors and help: "hang:RANK, drop:RANK, ...".
std::string faultInjectionForms();

// Parses "hang:RANK", "drop:RANK", "crash:RANK", "crash-photons:RANK" or "slow:RANK" (the kinds
// above) for a slave rank >= 1. Throws std::invalid_argument listing the accepted forms.
FaultInjection parseFaultInjection(const std::string& text);

}  // namespace prism

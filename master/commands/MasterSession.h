// Rank 0's side of a run, the same for every command: it loads the scene (with the command
// line's overrides, and every check that refuses a request before anything is allocated) and
// runs the run's cluster on a DispatchSession (master/dispatch/DispatchSession.h: the scene's
// broadcast, rank 0's build, the geometry, the dispatcher, and at the end the slaves' shut-down).
// `prism render`, `view` and `speedup` run on one; `sweep`, which times methods in one process,
// uses only its loading and its refusal to run under MPI.
//
//   MasterSession session(transport, options.render, err);
//   if (!session.load(checkOutputs)) return 1;   // reported, and the slaves told
//   try { session.start(); ... session.dispatcher() ... } catch (...) { exitCode = 1; }
//   return session.finish(exitCode);
#pragma once

#include <functional>
#include <iosfwd>
#include <string>

#include "master/commands/RenderOptions.h"
#include "master/dispatch/DispatchSession.h"
#include "scene/Scene.h"
#include "scene/SceneDescription.h"

namespace prism {

class Transport;

// Loads the scene the options name (refusing meshes past the memory limit before reading
// them), applies their overrides, and refuses settings, an image, tiles, a photon map or
// geometry that cannot fit (master/frame/ResourceCheck.h), all before the scene is broadcast
// or built, so no rank allocates for a refused request. Throws on any of these.
SceneDescription loadSceneWithOverrides(const RenderOptions& options);

class MasterSession {
 public:
  using GeometrySending = DispatchSession::GeometrySending;

  // transport null: one process, no slaves. Errors are reported to err.
  MasterSession(Transport* transport, RenderOptions options, std::ostream& err);

  // Runs the command's own checks of its arguments (output paths: `check` throws to refuse),
  // then loads the scene and chooses the job's instruction set from every rank's Hello. On failure
  // the error is printed ("prism: error: ..."), the slaves get it instead of a scene and stop, and
  // false is returned: the command exits with 1.
  bool load(const std::function<void()>& check = {});
  // Refuses the run before any scene is loaded, as load() does on failure. Returns 1.
  int refuse(const std::string& why) { return dispatch_.refuse(why); }
  // The scene to every rank and the dispatcher opened (DispatchSession::start).
  void start(bool keepEnvironment = false, GeometrySending sending = GeometrySending::AtStart) {
    dispatch_.start(description_, keepEnvironment, sending);
  }

  const RenderOptions& options() const { return options_; }
  const SceneDescription& description() const { return description_; }
  const Scene& scene() const { return dispatch_.scene(); }
  WorkDispatcher& dispatcher() { return dispatch_.dispatcher(); }
  SlaveLink& link() { return dispatch_.link(); }
  const SessionSetUp& setUp() const { return dispatch_.setUp(); }

  // The end of the run (DispatchSession::finish). Returns exitCode.
  int finish(int exitCode) { return dispatch_.finish(exitCode); }
  // The command's work (it returns the exit code), then finish(): an exception it throws is
  // reported ("prism: error: ...") and ends the run with exit code 1.
  int runToEnd(const std::function<int()>& work, std::ostream& out);

 private:
  RenderOptions options_;
  std::ostream& err_;
  SceneDescription description_;
  DispatchSession dispatch_;
};

}  // namespace prism

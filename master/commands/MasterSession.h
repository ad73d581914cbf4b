// Rank 0's side of a run, the same for every command: it loads the scene (with the command
// line's overrides, and every check that refuses a request before anything is allocated),
// broadcasts it to the slaves (or, when there is none to send, the reason, so they stop too),
// builds rank 0's Scene, opens the run's one dispatcher (its link to the slaves, whose roster is
// the one record of every rank, and rank 0's render threads) and, at the end, shuts the slaves
// down. `prism render`, `view` and `speedup` run on one; `sweep`, which times methods in one
// process, uses only its loading and its refusal to run under MPI.
//
//   MasterSession session(transport, options.render, err);
//   if (!session.load(checkOutputs)) return 1;   // reported, and the slaves told
//   try { session.start(); ... session.dispatcher() ... } catch (...) { exitCode = 1; }
//   return session.finish(exitCode);
#pragma once

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>

#include "master/commands/RenderOptions.h"
#include "master/runtime/GeometryShare.h"
#include "master/runtime/JobInstructionSet.h"
#include "master/runtime/WorkDispatcher.h"
#include "scene/Scene.h"
#include "scene/SceneDescription.h"

namespace prism {

class Transport;

// How long rank 0's scene broadcast may wait for the slaves (they may still be starting).
inline constexpr double kSceneBroadcastTimeoutSeconds = 600.0;

// Loads the scene the options name (refusing meshes past the memory limit before reading
// them), applies their overrides, and refuses settings, an image, tiles, a photon map or
// geometry that cannot fit (master/runtime/ResourceCheck.h), all before the scene is broadcast
// or built, so no rank allocates for a refused request. Throws on any of these.
SceneDescription loadSceneWithOverrides(const RenderOptions& options);

// What setting the run up cost on rank 0.
struct SessionSetUp {
  double parseSeconds = 0.0;
  double broadcastSeconds = 0.0;
  size_t broadcastBytes = 0;
  double buildSeconds = 0.0;
  JobInstructionSet instructionSet;  // what the kernels run on every rank, and why
  GeometrySharePlan geometryShare;   // MPI runs: who built the geometry, and why
};

class MasterSession {
 public:
  // transport null: one process, no slaves. Errors are reported to err.
  MasterSession(Transport* transport, RenderOptions options, std::ostream& err);
  ~MasterSession();
  MasterSession(const MasterSession&) = delete;
  MasterSession& operator=(const MasterSession&) = delete;

  // Runs the command's own checks of its arguments (output paths: `check` throws to refuse),
  // then loads the scene and chooses the job's instruction set from every rank's Hello. On failure
  // the error is printed ("prism: error: ..."), the slaves get it instead of a scene and stop, and
  // false is returned: the command exits with 1.
  bool load(const std::function<void()>& check = {});
  // Refuses the run before any scene is loaded, as load() does on failure. Returns 1.
  int refuse(const std::string& why);
  // When rank 0 broadcasts the geometry it built: before start() returns (set-up timed apart
  // from frames, as `speedup` measures), or as the first frame begins, while rank 0's render
  // threads already render it (`render`: the first pixel right after rank 0's build), if its
  // transfer is predicted to take kSendWhileRenderingSeconds or more (GeometryShare.h).
  enum class GeometrySending { AtStart, WhileRank0Renders };
  // Broadcasts the scene, waits for every slave to accept it (a slave's refusal ends the job
  // here, before any rank builds), chooses who builds the geometry (GeometryShare.h), builds
  // rank 0's Scene, broadcasts the geometry if so chosen (when: `sending`), and opens the run's
  // dispatcher. The scene takes the description's cube-map faces unless keepEnvironment (the
  // viewer shows them). Throws on failure; finish() still ends the slaves.
  void start(bool keepEnvironment = false, GeometrySending sending = GeometrySending::AtStart);

  const RenderOptions& options() const { return options_; }
  const SceneDescription& description() const { return description_; }
  const Scene& scene() const { return *scene_; }
  WorkDispatcher& dispatcher() { return *dispatcher_; }
  SlaveLink& link() { return dispatcher_->link(); }
  const SessionSetUp& setUp() const { return setUp_; }

  // The end of the run: the dispatcher's threads stop, then every slave is told to shut down
  // and waited for (the job is aborted when one is lost or does not answer: MPI_Finalize
  // would wait for it forever). Rank 0 interrupted by mpiexec's SIGTERM leaves at once
  // instead, before the SIGKILL that follows. Returns exitCode.
  int finish(int exitCode);
  // The command's work (it returns the exit code), then finish(): an exception it throws is
  // reported ("prism: error: ...") and ends the run with exit code 1.
  int runToEnd(const std::function<int()>& work, std::ostream& out);

 private:
  // Every slave's answer to the scene, then the plan; local builds are announced at once.
  void planGeometry(size_t descriptionBytes, double descriptionSeconds);
  // Tells the slaves waiting for the geometry that there will be none: they stop, and finish()
  // has nobody to shut down.
  void cancelGeometry(const std::string& why);

  Transport* transport_;
  RenderOptions options_;
  std::ostream& err_;
  SceneDescription description_;
  std::unique_ptr<Scene> scene_;
  std::unique_ptr<WorkDispatcher> dispatcher_;
  SessionSetUp setUp_;
  bool finished_ = false;
};

}  // namespace prism

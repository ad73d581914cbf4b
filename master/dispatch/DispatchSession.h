// Rank 0's side of a run's cluster, the same for every command: it chooses the job's
// instruction set from every rank's Hello, broadcasts the scene (or, when there is none to send,
// the reason, so the slaves stop too), waits for every slave to accept it, chooses who builds the
// geometry (GeometryShare.h), builds rank 0's Scene, shares the geometry, opens the run's one
// dispatcher (its link to the slaves, whose roster is the one record of every rank, and rank 0's
// render threads) and, at the end, shuts the slaves down. The command's MasterSession
// (master/commands/MasterSession.h) loads the scene and runs one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include "cluster/DistributionOptions.h"
#include "master/dispatch/GeometryShare.h"
#include "master/dispatch/JobInstructionSet.h"
#include "master/dispatch/WorkDispatcher.h"
#include "scene/Scene.h"
#include "scene/SceneDescription.h"
#include "util/InstructionSet.h"

namespace prism {

class Transport;

// What the command line decides of the run's cluster.
struct DispatchSettings {
  InstructionSet instructionSet = InstructionSet::Auto;  // Auto: the best every rank runs
  GeometryShareMode geometryShare = GeometryShareMode::Auto;
  DistributionOptions distribution;
  std::optional<uint64_t> memoryLimit;  // bytes a run may plan to use; default: physical memory
};

// What setting the run up cost on rank 0.
struct SessionSetUp {
  double parseSeconds = 0.0;
  double broadcastSeconds = 0.0;
  size_t broadcastBytes = 0;
  double buildSeconds = 0.0;
  JobInstructionSet instructionSet;  // what the kernels run on every rank, and why
  GeometrySharePlan geometryShare;   // MPI runs: who built the geometry, and why
};

class DispatchSession {
 public:
  // transport null: one process, no slaves. Errors are reported to err.
  DispatchSession(Transport* transport, DispatchSettings settings, std::ostream& err);
  ~DispatchSession();
  DispatchSession(const DispatchSession&) = delete;
  DispatchSession& operator=(const DispatchSession&) = delete;

  // Chooses the job's instruction set from every rank's Hello (they wait by the time the scene
  // is parsed) and notes it in setUp(). Throws when a rank does not say.
  InstructionSet chooseInstructionSet();
  // Refuses the run before any scene is sent: the slaves get the error instead of a scene and
  // stop, and it is printed ("prism: error: ..."). Returns 1.
  int refuse(const std::string& why);
  // When rank 0 broadcasts the geometry it built: before start() returns (set-up timed apart
  // from frames, as `speedup` measures), or as the first frame begins, while rank 0's render
  // threads already render it (`render`: the first pixel right after rank 0's build), if its
  // transfer is predicted to take kSendWhileRenderingSeconds or more (GeometryShare.h).
  enum class GeometrySending { AtStart, WhileRank0Renders };
  // Broadcasts the scene, waits for every slave to accept it (a slave's refusal ends the job
  // here, before any rank builds), chooses who builds the geometry, builds rank 0's Scene,
  // broadcasts the geometry if so chosen (when: `sending`), and opens the run's dispatcher. The
  // scene takes the description's cube-map faces unless keepEnvironment (the viewer shows
  // them). Throws on failure; finish() still ends the slaves.
  void start(SceneDescription& description, bool keepEnvironment, GeometrySending sending);

  const Scene& scene() const { return *scene_; }
  WorkDispatcher& dispatcher() { return *dispatcher_; }
  SlaveLink& link() { return dispatcher_->link(); }
  const SessionSetUp& setUp() const { return setUp_; }
  SessionSetUp& setUp() { return setUp_; }

  // The end of the run: the dispatcher's threads stop, then every slave is told to shut down
  // and waited for (the job is aborted when one is lost or does not answer: MPI_Finalize
  // would wait for it forever). Rank 0 interrupted by mpiexec's SIGTERM leaves at once
  // instead, before the SIGKILL that follows. Returns exitCode.
  int finish(int exitCode);

 private:
  // Every slave's answer to the scene, then the plan; local builds are announced at once.
  void planGeometry(const SceneDescription& description, size_t descriptionBytes,
                    double descriptionSeconds);
  // Tells the slaves waiting for the geometry that there will be none: they stop, and finish()
  // has nobody to shut down.
  void cancelGeometry(const std::string& why);

  Transport* transport_;
  DispatchSettings settings_;
  std::ostream& err_;
  std::unique_ptr<Scene> scene_;
  std::unique_ptr<WorkDispatcher> dispatcher_;
  SessionSetUp setUp_;
  bool finished_ = false;
};

}  // namespace prism

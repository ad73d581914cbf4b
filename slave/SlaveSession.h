// One slave's part of a job, from the scene to the end: receive the scene rank 0 broadcasts,
// build it and say Ready (or say why not), then serve rank 0's messages (slave/SlaveHandlers.h)
// while the render threads, the photon work and the heartbeat run (slave/SlaveWork.h), sending
// each finished tile and photon share as it comes, until rank 0's Shutdown, a failure, an
// interrupt or rank 0's silence; then stop the threads and end as each case needs.
#pragma once

#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "cluster/DistributionOptions.h"
#include "slave/SlaveLoop.h"
#include "transport/Transport.h"
#include "util/MemorySize.h"
#include "util/ThreadCount.h"
#include "wire/Messages.h"

namespace prism {

class Scene;
struct SlaveWork;

class SlaveSession {
 public:
  // Reads options.threads (resolved here, once for the rank: util/ThreadCount.h) and
  // masterTimeoutSeconds; memoryLimit as runSlave's.
  SlaveSession(Transport& transport, const DistributionOptions& options,
               const MemoryLimit& memoryLimit);
  ~SlaveSession();

  // The whole session; how the process should end.
  SlaveEnd run();

 private:
  // The set-up, a step at a time (the message list's set-up phase): each step sends rank 0 what
  // it waits for and takes its next broadcast. Hello: what this CPU runs (rank 0 chooses the
  // job's instruction set). Scene: the description (or rank 0's Error), checked against this
  // rank's memory and answered with SceneAccepted (or an Error saying why not). Build: rank 0's
  // built geometry (Geometry), the go-ahead (BuildGeometry) or an Error (the job ends); the
  // scene built and Ready sent. Rank 0's side: master/dispatch/DispatchSession.cpp.
  enum class SetUpStep { Hello, Scene, Build, Done };
  // Every step; the scene built and Ready sent, else how the session ends (rank 0 silent or
  // failed, the scene refused: reported to rank 0).
  std::optional<SlaveEnd> buildScene(double startSeconds);
  SetUpStep sayHello();
  std::variant<SetUpStep, SlaveEnd> takeScene();
  std::variant<SetUpStep, SlaveEnd> takePlanAndBuild(double startSeconds);
  // message, if the list says rank 0 sends it in set-up (an Error too); else throws
  // wire::WireError.
  static wire::Message setUpMessage(wire::Message message);
  // Rank 0's next broadcast into bytes; false (reported) when it does not come.
  bool receiveBroadcast(std::vector<uint8_t>& bytes);
  // The Scene as the plan says (rank 0's geometry, or built here), and Ready sent.
  std::unique_ptr<Scene> build(SceneDescription& description, const wire::Message& plan,
                               double startSeconds);
  // The message loop, until it ends; a failure in it is reported to rank 0.
  void serve();
  void loop();
  // Sends the finished tiles and photon share; false when rank 0 is gone.
  bool sendFinished();
  // The next message, after waiting (without the lock) up to the idle bound for one.
  std::optional<IncomingMessage> nextMessage();
  void stopOn(const char* why, bool masterLost);
  SlaveEnd finish();

  Transport& transport_;
  DistributionOptions options_;
  ThreadCount threads_;  // the rank's render and photon threads, which its Ready announces
  MemoryLimit memoryLimit_;
  std::optional<SceneDescription> description_;  // between the Scene and Build steps
  std::unique_ptr<SlaveWork> work_;
  bool interrupted_ = false;
  SlaveEnd end_;
};

}  // namespace prism

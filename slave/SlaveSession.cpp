#include "slave/SlaveSession.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <variant>

#include "caustics/CausticMapMemory.h"
#include "scene/GeometryMemory.h"
#include "scene/Scene.h"
#include "slave/ShutdownWait.h"
#include "slave/SlaveHandlers.h"
#include "slave/SlaveWork.h"
#include "util/InstructionSet.h"
#include "util/InterruptSignal.h"
#include "util/Parallel.h"
#include "util/ProcessStart.h"
#include "util/Stopwatch.h"
#include "wire/GeometryCodec.h"
#include "wire/Messages.h"

namespace prism {
namespace {

constexpr double kInterruptedShutdownSeconds = 0.8;
// The longest the message loop sleeps without news: the bound on noticing Ctrl-C or rank 0's
// silence. Messages, finished tiles and photon shares wake it at once.
constexpr double kIdleCheckSeconds = 0.1;

}  // namespace

SlaveSession::SlaveSession(Transport& transport, const DistributionOptions& options,
                           const MemoryLimit& memoryLimit)
    : transport_(transport),
      options_(options),
      threads_(ThreadCount::resolve(options.threads)),
      memoryLimit_(memoryLimit) {}

SlaveSession::~SlaveSession() = default;

SlaveEnd SlaveSession::run() {
  const double startSeconds = secondsSinceProcessStart().value_or(-1.0);  // before any work
  installInterruptHandlers();
  if (std::optional<SlaveEnd> end = buildScene(startSeconds)) return *end;
  serve();
  return finish();
}

std::optional<SlaveEnd> SlaveSession::buildScene(double startSeconds) {
  std::variant<SetUpStep, SlaveEnd> next = SetUpStep::Hello;
  while (const SetUpStep* step = std::get_if<SetUpStep>(&next)) {
    switch (*step) {
      case SetUpStep::Hello:
        next = sayHello();
        break;
      case SetUpStep::Scene:
        next = takeScene();
        break;
      case SetUpStep::Build:
        next = takePlanAndBuild(startSeconds);
        break;
      case SetUpStep::Done:
        return std::nullopt;
    }
  }
  return std::get<SlaveEnd>(next);
}

SlaveSession::SetUpStep SlaveSession::sayHello() {
  // Rank 0 chooses the job's instruction set from every rank's answer before it broadcasts the
  // scene (master/dispatch/JobInstructionSet.h).
  try {
    transport_.send(0, wire::encode(wire::HelloMessage{runnableInstructionSets(), cpuModelName()}));
  } catch (const std::invalid_argument& e) {  // a bad PRISM_TEST_CPU_LIMIT: rank 0 reports it
    transport_.send(0, wire::encode(wire::ErrorMessage{e.what()}));
  }
  return SetUpStep::Scene;
}

std::variant<SlaveSession::SetUpStep, SlaveEnd> SlaveSession::takeScene() {
  std::vector<uint8_t> bytes;
  if (!receiveBroadcast(bytes)) return SlaveEnd{1, true};
  // The description, checked against this rank's memory before any rank builds: rank 0 waits
  // for every slave's answer.
  try {
    const wire::Message message = setUpMessage(wire::decodeMessage(bytes));
    // Rank 0 broadcasts an error instead of a scene when it cannot read the file; it reports it.
    if (message.type == wire::MessageType::Error) return SlaveEnd{1};
    description_ = wire::decodeScene(message);
    // Rank 0 checked the scene against its own limit; this rank may be a smaller machine.
    checkGeometryFits(*description_, memoryLimit_);
    transport_.send(0, wire::encode(wire::SceneAcceptedMessage{availableCores(), machineCores(),
                                                               transport_.ranksOnThisNode()}));
  } catch (const std::exception& e) {
    transport_.send(
        0, wire::encode(wire::ErrorMessage{std::string("cannot build the scene: ") + e.what()}));
    description_.reset();
  }
  return SetUpStep::Build;
}

std::variant<SlaveSession::SetUpStep, SlaveEnd> SlaveSession::takePlanAndBuild(
    double startSeconds) {
  // Whether to build: rank 0's own build (Geometry), a go-ahead (BuildGeometry), or an Error (a
  // slave refused the scene, or rank 0 could not build it): the job ends.
  std::vector<uint8_t> bytes;
  if (!receiveBroadcast(bytes)) return SlaveEnd{1, true};
  try {
    const wire::Message plan = setUpMessage(wire::decodeMessage(std::move(bytes)));
    if (!description_ || plan.type == wire::MessageType::Error) return SlaveEnd{1};
    work_ = std::make_unique<SlaveWork>(transport_, build(*description_, plan, startSeconds),
                                        threads_, memoryLimit_);
    description_.reset();
    return SetUpStep::Done;
  } catch (const std::exception& e) {
    transport_.send(
        0, wire::encode(wire::ErrorMessage{std::string("cannot build the scene: ") + e.what()}));
    awaitShutdown(transport_, options_.masterTimeoutSeconds);
    return SlaveEnd{1};
  }
}

wire::Message SlaveSession::setUpMessage(wire::Message message) {
  if (!wire::goesTo(message.type, wire::Direction::ToSlave) ||
      !wire::belongsTo(message.type, wire::Phase::SetUp)) {
    throw wire::WireError(std::string("rank 0 sent ") + wire::messageTypeName(message.type) +
                          " while the job was being set up");
  }
  return message;
}

bool SlaveSession::receiveBroadcast(std::vector<uint8_t>& bytes) {
  try {
    transport_.broadcast(bytes, options_.masterTimeoutSeconds);
    return true;
  } catch (const TransportError& e) {
    std::fprintf(stderr, "prism: rank %d: %s\n", transport_.rank(), e.what());
    return false;
  }
}

std::unique_ptr<Scene> SlaveSession::build(SceneDescription& description, const wire::Message& plan,
                                           double startSeconds) {
  const auto buildStart = SteadyClock::now();
  std::optional<CubeMapDesc> environment = std::exchange(description.environment, std::nullopt);
  std::unique_ptr<Scene> scene;
  if (plan.type == wire::MessageType::Geometry) {
    SceneGeometry geometry = wire::decode<SceneGeometry>(plan);
    wire::checkGeometryFitsScene(geometry, description);
    scene = std::make_unique<Scene>(description, std::move(environment), std::move(geometry));
  } else {
    wire::decode<wire::BuildGeometryMessage>(plan);  // anything else is refused
    scene = std::make_unique<Scene>(description, std::move(environment));
  }
  checkCausticMapsFit(*scene, memoryLimit_);  // before any map is built
  transport_.send(0, wire::encode(wire::ReadyMessage{secondsSince(buildStart), threads_.value(),
                                                     startSeconds, transport_.setUpSeconds()}));
  return scene;
}

void SlaveSession::serve() {
  try {
    work_->loopLock.lock();
    loop();
    work_->loopLock.unlock();
  } catch (const std::exception& e) {
    if (work_->loopLock.owns_lock()) work_->loopLock.unlock();
    work_->heartbeat.stop();
    transport_.send(0, wire::encode(wire::ErrorMessage{e.what()}));
    end_.exitCode = 1;
  }
  work_->heartbeat.stop();
}

void SlaveSession::loop() {
  auto lastHeard = SteadyClock::now();
  while (!work_->pool.failed()) {
    if (interruptRequested()) {
      interrupted_ = true;
      return;
    }
    if (!sendFinished()) return stopOn("rank 0 is gone, stopping", true);
    std::optional<IncomingMessage> incoming = nextMessage();
    if (!incoming) {
      if (secondsSince(lastHeard) > options_.masterTimeoutSeconds) {
        char why[80];
        std::snprintf(why, sizeof why, "no word from rank 0 for %.0f s, giving up",
                      options_.masterTimeoutSeconds);
        return stopOn(why, true);
      }
      continue;
    }
    lastHeard = SteadyClock::now();
    const wire::Message message = wire::decodeMessage(incoming->bytes);
    if (handleMessage(*work_, message, incoming->bytes) == AfterMessage::Stop) return;
  }
}

bool SlaveSession::sendFinished() {
  bool reachable = !work_->heartbeat.masterGone();
  for (wire::TileResultMessage& result : work_->outbox.take()) {
    if (!work_->frames.finish(result.frame, result.result.tileIndex)) continue;  // stale
    reachable = transport_.send(0, wire::encode(result)) && reachable;
  }
  if (std::optional<std::vector<uint8_t>> share = work_->photons.finished()) {
    reachable = transport_.send(0, std::move(*share)) && reachable;
  }
  return reachable;
}

std::optional<IncomingMessage> SlaveSession::nextMessage() {
  std::optional<IncomingMessage> incoming = transport_.poll();
  if (incoming) return incoming;
  // Sleeps without the lock (the heartbeat may send meanwhile) until a message may have come,
  // a tile or photon share finished, or the idle bound passes.
  work_->unlocked([this] { transport_.awaitActivity(kIdleCheckSeconds); });
  return transport_.poll();
}

void SlaveSession::stopOn(const char* why, bool masterLost) {
  std::fprintf(stderr, "prism: rank %d: %s\n", transport_.rank(), why);
  end_ = {1, masterLost};
}

SlaveEnd SlaveSession::finish() {
  try {
    work_->stop();
  } catch (const std::exception& e) {
    transport_.send(
        0, wire::encode(wire::ErrorMessage{std::string("render thread failed: ") + e.what()}));
    awaitShutdown(transport_, options_.masterTimeoutSeconds);
    return {1};
  }
  if (work_->shutdownReceived) {
    transport_.send(0,
                    wire::encode(wire::ShutdownMessage{}));  // acknowledged: the master may finish
  } else if (interrupted_) {
    // Usually every rank got the signal (mpiexec sends SIGTERM to all) and rank 0 is writing
    // its partial frame: wait for its shutdown a little, well inside mpiexec's one second
    // before SIGKILL. A slave interrupted alone tells rank 0, which ends the run with an error.
    transport_.send(
        0, wire::encode(wire::ErrorMessage{std::string("stopped by ") + interruptSignalName()}));
    awaitShutdown(transport_, kInterruptedShutdownSeconds);
    // SIGTERM comes from mpiexec ending the job: MPI_Finalize would wait for the SIGKILL.
    if (interruptSignalName() == std::string("SIGTERM")) std::_Exit(kInterruptedExitCode);
    return {kInterruptedExitCode};
  } else if (!end_.masterLost) {
    awaitShutdown(transport_, options_.masterTimeoutSeconds);  // after an error this rank reported
  }
  return end_;
}

}  // namespace prism

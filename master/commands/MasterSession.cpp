#include "master/commands/MasterSession.h"

#include <ostream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "caustics/CausticMapMemory.h"
#include "master/runtime/ResourceCheck.h"
#include "master/runtime/SlaveRollCall.h"
#include "master/runtime/SlaveShutdown.h"
#include "parse/SceneLoader.h"
#include "scene/SceneValidation.h"
#include "transport/Transport.h"
#include "util/InterruptSignal.h"
#include "util/Parallel.h"
#include "util/Stopwatch.h"
#include "wire/GeometryCodec.h"
#include "wire/Messages.h"

namespace prism {

SceneDescription loadSceneWithOverrides(const RenderOptions& options) {
  const MemoryLimit limit = memoryLimitOrPhysical(options.memoryLimit);
  SceneDescription description = loadScene(options.scenePath, limit);
  applyOverrides(options, description.render);
  applyOverrides(options, description.caustics);
  applyOverrides(options, description.camera);
  validate(description);
  checkRenderFits(description.render, limit);
  checkTilesFit(description.render, options.distribution.tileSize, limit);
  checkCausticsFit(description.caustics, description.lights.size(), limit);
  checkSceneFits(description, options.distribution.tileSize, limit);
  return description;
}

MasterSession::MasterSession(Transport* transport, RenderOptions options, std::ostream& err)
    : transport_(transport), options_(std::move(options)), err_(err) {}

MasterSession::~MasterSession() {
  // A command that threw past finish(): its threads stop; the slaves are left to their
  // master-timeout (the process is ending with an error anyway).
  if (dispatcher_) dispatcher_->cancel();
}

bool MasterSession::load(const std::function<void()>& check) {
  try {
    if (check) check();
    const auto start = SteadyClock::now();
    description_ = loadSceneWithOverrides(options_);
    setUp_.parseSeconds = secondsSince(start);
    // After the parse, which the slaves' start-up overlaps: their Hellos are waiting by now.
    setUp_.instructionSet =
        chooseJobInstructionSet(transport_, options_.instructionSet, kSceneBroadcastTimeoutSeconds);
    description_.render.instructionSet = setUp_.instructionSet.chosen;
    return true;
  } catch (const std::exception& e) {
    refuse(e.what());
    return false;
  }
}

int MasterSession::refuse(const std::string& why) {
  if (transport_) {
    std::vector<uint8_t> bytes = wire::encode(wire::ErrorMessage{why});
    transport_->broadcast(bytes, kSceneBroadcastTimeoutSeconds);
  }
  err_ << "prism: error: " << why << "\n";
  finished_ = true;  // the slaves stop on the error: there is nobody to shut down
  return 1;
}

void MasterSession::start(bool keepEnvironment, GeometrySending sending) {
  if (transport_) {
    const auto start = SteadyClock::now();
    std::vector<uint8_t> bytes = wire::encodeScene(description_);
    const auto sendStart = SteadyClock::now();
    transport_->broadcast(bytes, kSceneBroadcastTimeoutSeconds);
    const double linkSeconds = secondsSince(sendStart);
    setUp_.broadcastSeconds = secondsSince(start);
    setUp_.broadcastBytes = bytes.size();
    planGeometry(bytes.size(), linkSeconds);
  }
  const bool sendGeometry = setUp_.geometryShare.broadcast;
  const auto buildStart = SteadyClock::now();
  try {
    scene_ = keepEnvironment
                 ? std::make_unique<Scene>(description_)
                 : std::make_unique<Scene>(description_,
                                           std::exchange(description_.environment, std::nullopt));
  } catch (const std::exception& e) {
    if (sendGeometry) cancelGeometry(std::string("rank 0 cannot build the scene: ") + e.what());
    throw;
  }
  setUp_.buildSeconds = secondsSince(buildStart);
  const auto sendGeometryNow = [this](bool rank0Renders) {
    setUp_.geometryShare.sentWhileRendering = rank0Renders;
    const auto sendStart = SteadyClock::now();
    std::vector<uint8_t> bytes = wire::encode(scene_->geometry());
    transport_->broadcast(bytes, kSceneBroadcastTimeoutSeconds);
    setUp_.geometryShare.sentBytes = bytes.size();
    setUp_.geometryShare.sentSeconds = secondsSince(sendStart);
  };
  const bool whileRendering = sendGeometry && sending == GeometrySending::WhileRank0Renders &&
                              setUp_.geometryShare.transferSeconds >= kSendWhileRenderingSeconds;
  if (sendGeometry && !whileRendering) sendGeometryNow(false);
  checkCausticMapsFit(*scene_, memoryLimitOrPhysical(options_.memoryLimit));
  dispatcher_ = std::make_unique<WorkDispatcher>(*scene_, transport_, options_.distribution);
  if (whileRendering) dispatcher_->openWith(sendGeometryNow);
}

void MasterSession::planGeometry(size_t descriptionBytes, double descriptionSeconds) {
  std::vector<wire::Message> answers;
  try {
    answers = firstMessageOfEachSlave(*transport_, wire::MessageType::SceneAccepted,
                                      kSceneBroadcastTimeoutSeconds,
                                      "did not say whether the scene fits");
  } catch (const std::exception& e) {
    cancelGeometry(e.what());
    throw std::runtime_error(std::string(e.what()) + " (before any rank built the scene)");
  }
  std::vector<BuildPlace> slaves;
  for (size_t r = 1; r < answers.size(); ++r) {
    const auto accepted = wire::decode<wire::SceneAcceptedMessage>(answers[r]);
    slaves.push_back({accepted.threads, accepted.cores, accepted.ranksOnNode});
  }
  size_t triangles = 0;
  for (const MeshDesc& mesh : description_.meshes) triangles += mesh.indices.size() / 3;
  const BuildPlace rank0{availableCores(), machineCores(), transport_->ranksOnThisNode()};
  setUp_.geometryShare = planGeometryShare(options_.geometryShare, triangles, descriptionBytes,
                                           descriptionSeconds, rank0, slaves);
  if (!setUp_.geometryShare.broadcast) {
    std::vector<uint8_t> bytes = wire::encode(wire::BuildGeometryMessage{});
    transport_->broadcast(bytes, kSceneBroadcastTimeoutSeconds);
  }
}

void MasterSession::cancelGeometry(const std::string& why) {
  std::vector<uint8_t> bytes = wire::encode(wire::ErrorMessage{why});
  transport_->broadcast(bytes, kSceneBroadcastTimeoutSeconds);
  finished_ = true;
}

int MasterSession::runToEnd(const std::function<int()>& work, std::ostream& out) {
  int exitCode = 0;
  try {
    exitCode = work();
  } catch (const std::exception& e) {
    err_ << "prism: error: " << e.what() << "\n";
    exitCode = 1;
  }
  out.flush();
  return finish(exitCode);
}

int MasterSession::finish(int exitCode) {
  if (finished_) return exitCode;
  if (dispatcher_ && dispatcher_->openingPending()) {
    // No frame began, so the slaves still wait for rank 0's geometry: an Error in its place
    // ends them, as when rank 0's build fails.
    dispatcher_->stop();
    try {
      dispatcher_->join();
    } catch (const std::exception&) {  // the run's failure was reported already
    }
    cancelGeometry("rank 0 stopped before it sent the geometry");
    return exitCode;
  }
  finished_ = true;
  std::vector<bool> silent;
  if (dispatcher_) {
    silent = link().retiredRanks();
    dispatcher_->stop();
    try {
      dispatcher_->join();
    } catch (const std::exception& e) {
      if (exitCode == 0) {  // a render thread's failure the command did not see
        err_ << "prism: error: " << e.what() << "\n";
        exitCode = 1;
      }
    }
  }
  err_.flush();
  if (transport_ && interruptRequested() && interruptSignalName() == std::string("SIGTERM")) {
    leaveEndingJob(*transport_, exitCode);
  }
  return shutDownSlaves(transport_, exitCode, silent, err_);
}

}  // namespace prism

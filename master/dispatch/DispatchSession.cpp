#include "master/dispatch/DispatchSession.h"

#include <ostream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "caustics/CausticMapMemory.h"
#include "master/dispatch/SlaveShutdown.h"
#include "transport/Transport.h"
#include "util/InterruptSignal.h"
#include "util/Parallel.h"
#include "util/PhysicalMemory.h"
#include "util/Stopwatch.h"
#include "wire/Messages.h"

namespace prism {

DispatchSession::DispatchSession(Transport* transport, DispatchSettings settings, std::ostream& err)
    : transport_(transport), settings_(std::move(settings)), err_(err) {}

DispatchSession::~DispatchSession() {
  // A command that threw past finish(): its threads stop; the slaves are left to their
  // master-timeout (the process is ending with an error anyway).
  if (dispatcher_) dispatcher_->cancel();
}

InstructionSet DispatchSession::chooseInstructionSet() {
  setUp_.instructionSet =
      chooseJobInstructionSet(transport_, settings_.instructionSet, kSceneBroadcastTimeoutSeconds);
  return setUp_.instructionSet.chosen;
}

int DispatchSession::refuse(const std::string& why) {
  if (transport_) {
    std::vector<uint8_t> bytes = wire::encode(wire::ErrorMessage{why});
    transport_->broadcast(bytes, kSceneBroadcastTimeoutSeconds);
  }
  err_ << "prism: error: " << why << "\n";
  finished_ = true;  // the slaves stop on the error: there is nobody to shut down
  return 1;
}

void DispatchSession::start(SceneDescription& description, bool keepEnvironment,
                            GeometrySending sending) {
  if (transport_) {
    const auto start = SteadyClock::now();
    std::vector<uint8_t> bytes = wire::encodeScene(description);
    const auto sendStart = SteadyClock::now();
    transport_->broadcast(bytes, kSceneBroadcastTimeoutSeconds);
    const double linkSeconds = secondsSince(sendStart);
    setUp_.broadcastSeconds = secondsSince(start);
    setUp_.broadcastBytes = bytes.size();
    planGeometry(description, bytes.size(), linkSeconds);
  }
  const bool sendGeometry = setUp_.geometryShare.broadcast;
  const auto buildStart = SteadyClock::now();
  try {
    scene_ = keepEnvironment
                 ? std::make_unique<Scene>(description)
                 : std::make_unique<Scene>(description,
                                           std::exchange(description.environment, std::nullopt));
  } catch (const std::exception& e) {
    if (sendGeometry) cancelGeometry(std::string("rank 0 cannot build the scene: ") + e.what());
    throw;
  }
  setUp_.buildSeconds = secondsSince(buildStart);
  const bool whileRendering = sendGeometry && sending == GeometrySending::WhileRank0Renders &&
                              setUp_.geometryShare.transferSeconds >= kSendWhileRenderingSeconds;
  if (sendGeometry && !whileRendering) {
    broadcastGeometry(*transport_, scene_->geometry(), false, setUp_.geometryShare);
  }
  checkCausticMapsFit(*scene_, memoryLimitOrPhysical(settings_.memoryLimit));
  dispatcher_ = std::make_unique<WorkDispatcher>(*scene_, transport_, settings_.distribution);
  if (whileRendering) dispatcher_->sendGeometryAtOpening(setUp_.geometryShare);
}

void DispatchSession::planGeometry(const SceneDescription& description, size_t descriptionBytes,
                                   double descriptionSeconds) {
  std::vector<wire::SceneAcceptedMessage> answers;
  try {
    answers = firstOfEachSlave<wire::SceneAcceptedMessage>(
        *transport_, kSceneBroadcastTimeoutSeconds, "did not say whether the scene fits");
  } catch (const std::exception& e) {
    cancelGeometry(e.what());
    throw std::runtime_error(std::string(e.what()) + " (before any rank built the scene)");
  }
  std::vector<BuildPlace> slaves;
  for (size_t r = 1; r < answers.size(); ++r) {
    slaves.push_back({answers[r].threads, answers[r].cores, answers[r].ranksOnNode});
  }
  size_t triangles = 0;
  for (const MeshDesc& mesh : description.meshes) triangles += mesh.indices.size() / 3;
  const BuildPlace rank0{availableCores(), machineCores(), transport_->ranksOnThisNode()};
  setUp_.geometryShare = planGeometryShare(settings_.geometryShare, triangles, descriptionBytes,
                                           descriptionSeconds, rank0, slaves);
  if (!setUp_.geometryShare.broadcast) {
    std::vector<uint8_t> bytes = wire::encode(wire::BuildGeometryMessage{});
    transport_->broadcast(bytes, kSceneBroadcastTimeoutSeconds);
  }
}

void DispatchSession::cancelGeometry(const std::string& why) {
  std::vector<uint8_t> bytes = wire::encode(wire::ErrorMessage{why});
  transport_->broadcast(bytes, kSceneBroadcastTimeoutSeconds);
  finished_ = true;
}

int DispatchSession::finish(int exitCode) {
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

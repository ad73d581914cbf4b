#include "slave/SlaveHandlers.h"

#include <map>
#include <memory>
#include <utility>

#include "slave/SlaveWork.h"
#include "transport/Transport.h"
#include "wire/TileJobWire.h"

namespace prism {
namespace {

using Next = AfterMessage;

struct Received {
  const wire::Message& message;
  const std::vector<uint8_t>& bytes;
};

Next onShutdown(SlaveWork& work, const Received&) {
  work.shutdownReceived = true;  // acknowledged once the threads have stopped
  return Next::Stop;
}

// The viewer's next frame: the frames it no longer wants end, their queued tiles are dropped.
Next onView(SlaveWork& work, const Received& r) {
  wire::ViewMessage next = wire::decode<wire::ViewMessage>(r.message);
  work.frames.startView(next.frame, next.liveFrom, std::move(next.view));
  work.jobs.dropBefore(next.liveFrom);
  return Next::Continue;
}

// A link probe: straight back, as it came.
Next onEcho(SlaveWork& work, const Received& r) {
  work.transport.send(0, r.bytes);
  return Next::Continue;
}

Next onTileJob(SlaveWork& work, const Received& r) {
  const wire::TileJobMessage job = wire::decode<wire::TileJobMessage>(r.message);
  FrameWork* frame = work.frames.frameOfJob(job.frame);
  if (!frame) return Next::Continue;  // its frame has ended
  ++frame->received;
  frame->held.insert(job.tileIndex);  // with the count: no heartbeat sees it received, not held
  // The first tile of a caustic-map pass may build the maps.
  std::shared_ptr<const RenderPass> pass = work.unlocked([&] {
    return work.photons.pass(passTerms(job), !frame->view || frame->view->causticMapBlur);
  });
  TileJob tile = tileJobFromMessage(job, frame->view, std::move(pass));
  tile.frameEnded = frame->ended;
  work.jobs.push(std::move(tile));
  return Next::Continue;
}

Next onPhotonJob(SlaveWork& work, const Received& r) {
  // Waits for a share still being traced.
  work.unlocked([&] { work.photons.start(wire::decode<wire::PhotonJobMessage>(r.message)); });
  return Next::Continue;
}

Next onPhotonCancel(SlaveWork& work, const Received& r) {
  work.photons.cancel(wire::decode<wire::PhotonCancelMessage>(r.message).pass);
  return Next::Continue;
}

Next onPhotonMap(SlaveWork& work, const Received& r) {
  // Builds the kd-tree.
  work.unlocked([&] { work.photons.acceptMap(wire::decode<wire::PhotonMapMessage>(r.message)); });
  return Next::Continue;
}

Next onPhotonRadiiJob(SlaveWork& work, const Received& r) {
  // Waits for a share still being finished.
  work.unlocked(
      [&] { work.photons.findRadii(wire::decode<wire::PhotonRadiiJobMessage>(r.message)); });
  return Next::Continue;
}

Next onPhotonRadii(SlaveWork& work, const Received& r) {
  // Builds the disc tree.
  work.unlocked(
      [&] { work.photons.acceptRadii(wire::decode<wire::PhotonRadiiMessage>(r.message)); });
  return Next::Continue;
}

Next onPhotonMapAgain(SlaveWork& work, const Received& r) {
  work.photons.reuseMap(wire::decode<wire::PhotonMapAgainMessage>(r.message));
  return Next::Continue;
}

using Handler = Next (*)(SlaveWork&, const Received&);

// The message types a slave receives, and who serves each.
const std::map<wire::MessageType, Handler>& handlers() {
  using Type = wire::MessageType;
  static const std::map<Type, Handler> table = {
      {Type::Shutdown, onShutdown},
      {Type::View, onView},
      {Type::Echo, onEcho},
      {Type::TileJob, onTileJob},
      {Type::PhotonJob, onPhotonJob},
      {Type::PhotonCancel, onPhotonCancel},
      {Type::PhotonMap, onPhotonMap},
      {Type::PhotonRadiiJob, onPhotonRadiiJob},
      {Type::PhotonRadii, onPhotonRadii},
      {Type::PhotonMapAgain, onPhotonMapAgain},
  };
  return table;
}

}  // namespace

AfterMessage handleMessage(SlaveWork& work, const wire::Message& message,
                           const std::vector<uint8_t>& bytes) {
  const auto handler = handlers().find(message.type);
  if (handler == handlers().end()) return Next::Continue;
  return handler->second(work, Received{message, bytes});
}

}  // namespace prism

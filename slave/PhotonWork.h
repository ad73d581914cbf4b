// The caustic side of a slave: traces the photon shares and finds the shares of photon radii
// the master asks for (on a thread of its own, so the main thread keeps its heartbeat going),
// holds the photon map of the current pass for the tiles that need it, and builds the caustic
// maps.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "caustics/CausticMapEstimator.h"
#include "caustics/PhotonMap.h"
#include "caustics/PhotonTracer.h"
#include "render/RenderPass.h"
#include "scene/Scene.h"
#include "util/MemorySize.h"
#include "wire/Messages.h"
#include "wire/TileJobWire.h"

namespace prism {

class Transport;

class PhotonWork {
 public:
  // memoryLimit: this rank's, against which caustic maps the viewer switches on are checked.
  PhotonWork(const Scene& scene, int threads, Transport& transport, const MemoryLimit& memoryLimit);

  // Traces this rank's share of a pass; waits for a share still being traced first.
  void start(const wire::PhotonJobMessage& job);
  // Finds this rank's share of the radii of the map waiting for them.
  void findRadii(const wire::PhotonRadiiJobMessage& job);
  // Rank 0 dropped this pass: the share being traced, or whose radii are being found, stops
  // within a chunk of photons and is not sent, so this rank's threads are free for the next
  // frame's tiles at once.
  void cancel(uint32_t pass);
  // The finished share's message, once there is one (none for a cancelled pass).
  std::optional<std::vector<uint8_t>> finished();

  // A map whose gather needs per-photon radii waits for them (PhotonRadii), after this rank
  // finds its share if asked (PhotonRadiiJob); any other gathers at once.
  void acceptMap(wire::PhotonMapMessage&& message);
  void acceptRadii(wire::PhotonRadiiMessage&& message);
  // The kept map serves another pass: its radii and discs are not found again.
  void reuseMap(const wire::PhotonMapAgainMessage& message);

  // The render pass a tile job names; throws when it needs a photon map this rank lacks.
  // `blur`: the current view's caustic-map blur switch.
  std::shared_ptr<const RenderPass> pass(const PassTerms& terms, bool blur);

  // Waits for the work still running on threads of its own.
  void wait();

 private:
  // A photon map received, its gather waiting for the radii.
  struct PendingMap {
    uint32_t pass = 0;
    std::shared_ptr<const PhotonMap> map;
    PhotonGatherSettings gather;
    bool keep = false;
  };
  using Work = std::function<std::vector<uint8_t>()>;

  void run(uint32_t pass, Work work);
  PendingMap& pendingFor(uint32_t pass, const char* what);
  void useGather(uint32_t pass, std::shared_ptr<const CausticEstimator> gather, bool keep);
  std::shared_ptr<const RenderPass> causticMapPass(uint32_t index, bool blur);
  std::shared_ptr<const CausticMapEstimator>& causticMaps(bool blur);

  const Scene& scene_;
  int threads_;
  Transport& transport_;
  std::unique_ptr<PhotonTracer> tracer_;
  std::future<std::optional<std::vector<uint8_t>>> running_;
  uint32_t runningPass_ = 0;
  std::atomic<bool> cancel_{false};
  std::optional<PendingMap> pending_;
  uint32_t mapPass_ = 0;
  std::shared_ptr<const CausticEstimator> caustics_;  // the photon map of pass mapPass_
  // The last map sent with keep, as a gather, and its pass: the viewer names it again for every
  // later view's pass 1 (master/live/LiveRenderer.h), where sending and finding its radii again
  // held this rank's tiles up after every pause of the camera.
  std::shared_ptr<const CausticEstimator> kept_;
  uint32_t keptPass_ = 0;
  std::map<std::pair<bool, bool>, std::shared_ptr<const RenderPass>> passes_;  // (direct, caustics)
  std::optional<std::string> mapsRefusal_;  // why caustic maps cannot be built here, if so
  // Caustic maps by blur switch, built on first use and kept until the other setting's are
  // built: they depend on the scene alone.
  std::map<bool, std::shared_ptr<const CausticMapEstimator>> causticMaps_;
  std::future<std::shared_ptr<const CausticMapEstimator>> eagerMaps_;  // with the scene's blur
  std::map<bool, std::shared_ptr<const RenderPass>> mapPasses_;        // by blur switch
};

}  // namespace prism

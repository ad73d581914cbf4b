// The viewer's renderer: renders frame after frame of one Scene while the camera moves, on rank
// 0's threads and, in an MPI run, on the slaves. No Qt here; the viewer listens through
// LiveListener.
//
// The frame loop is real time. While the camera moves, every frame renders the newest view at 1
// sample per pixel, at full resolution unless a frame would miss the frame-time target: then each
// side takes the largest share that fits, 3/4, 2/3, 1/2, 1/3, …
// (master/live/ResolutionGovernor.h, down to 1/previewScale), and the resolution comes back as
// soon as a frame fits again. Frames are pipelined: once every tile of the current frame has been
// handed out, the next frame (the newest view, or the next pass of a still one) is queued on the
// work dispatcher, so render threads and slaves go straight on to its tiles while the last ones of
// the frame before return (except around photon passes: a slave holds one photon map at a time, and
// the coordinator traces photons itself). The first frame of a view is always finished (a move
// shows within about one frame time); a view that arrives meanwhile is rendered by the next frame.
// Refinement passes of a still view are ended at once by a move.
//
// A view's passes: its first frame is pass 1 when it is full resolution at the view's samples
// per pixel, else pass 0 (a reduced or 1-spp frame, not averaged); passes 1..maxPasses follow at
// full resolution with samplesPerPixel samples each while the camera is still, every one with
// its own seed so that their average converges (pass 1 uses the scene's seed: it is exactly the
// image `prism render` makes, and a full-resolution 1-spp frame while moving is exactly
// `prism render --spp 1` of that view). Each pass is its own frame on the wire (a new frame id).
//
// The listener hears of passes in order: a pass's start, its tiles, its end, then the next
// pass's (whose early tiles were held meanwhile), so it never has two passes open at once.
//
// With caustic mapping on, every pass adds the caustic maps' caustics: each rank builds the maps
// from the scene once per blur setting and keeps them, since they do not depend on the camera,
// so every frame looks them up at its own resolution.
//
// With photon-mapped caustics on, every full-resolution pass i ≥ 1 first traces a photon pass of
// its own (master/frame/PhotonPass.h, across the ranks) and gathers from it as progressiveGather
// (caustics/GatherRadius.h) says: per-photon k-NN radii shrunk by r²(i+1) = r²(i)·(i + α)/(i + 1),
// or the scene's fixed caustics.radius shrunk the same way. So the average of passes 1..N that
// the window shows is progressive photon mapping with N passes, as `prism render --progressive`
// computes it; with per-photon radii pass 1 is `prism render`'s classic estimate. The photon pass
// number (which keys the photon streams and names the map on the wire) is the pass's frame id,
// so it is unique per pass. Photons do not depend on the view, so the first view's pass 1 (its
// map, and rank 0's radii and discs) serves every later view's pass 1 for the same budget: after
// a move the caustic costs its gathers only. Slaves keep that map too (sent with keep) and are
// told to gather from it again (PhotonMapAgain). Frames while moving (pass 0) render no photon
// caustics, and a move cancels a photon pass being traced (its map is dropped), so it never waits
// for one.
//
// Every pass is a frame of the one work dispatcher (master/dispatch/WorkDispatcher.h), which hands
// its tiles to rank 0's threads and the slaves exactly as for `prism render`: the same leases,
// heartbeats (a slave's lost tiles are re-issued at once, a silent slave retired in seconds),
// and late or duplicate results dropped.
//
// run() is the coordinator: the only thread that talks to the slaves, the only thread that
// calls the listener, and the one that traces photons. setView() and stop() may be called from
// any thread and never wait for photons.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "caustics/CausticMapEstimator.h"
#include "caustics/PhotonGatherSettings.h"
#include "caustics/PhotonTracer.h"
#include "cluster/DistributionOptions.h"
#include "master/dispatch/SlaveLink.h"
#include "master/dispatch/WorkDispatcher.h"
#include "master/frame/PhotonPass.h"
#include "master/live/ResolutionGovernor.h"
#include "render/RayCounters.h"
#include "render/RenderPass.h"
#include "render/RenderView.h"
#include "render/Tile.h"
#include "scene/Scene.h"
#include "util/MemorySize.h"
#include "util/Stopwatch.h"

namespace prism {

struct LiveOptions {
  // Threads, tile size (0: automatic for each pass's resolution), schedule, leases.
  DistributionOptions distribution;
  // While moving, a frame may drop to 3/4, 2/3, 1/2, 1/3, … down to 1/previewScale of each side
  // to meet frameTimeSeconds; 1: always full resolution.
  int previewScale = 4;
  int maxPasses = 64;                  // full-resolution passes per view; then the renderer idles
  double statsInterval = 0.25;         // seconds between LiveListener::statsUpdated calls
  double frameTimeSeconds = 1.0 / 30;  // target for frames while moving; ≤ 0: none
  bool pipeline = true;                // queue the next frame before the current one returns
  // Caustic maps the user switches on are refused when they cannot fit (causticMapsRefusal).
  MemoryLimit memoryLimit;
};

// What the user controls.
struct ViewSettings {
  CameraDesc camera;
  int samplesPerPixel = 1;  // per full-resolution pass
  DebugView debugView = DebugView::Image;
  CausticMethod caustics = CausticMethod::None;  // photon map: one photon pass per full pass
  uint64_t photonsPerPass = 0;                   // photon budget; 0: the scene's
  bool causticMapBlur = true;                    // caustic map: the scene's blur, or none
  // The viewer's own number for the request, carried to the passes that render it
  // (PassInfo::viewTag): a viewer over a connection knows its views by it.
  uint64_t tag = 0;
  // Full-resolution passes of this view at most (≤ LiveOptions::maxPasses); 0: the renderer's.
  int maxPasses = 0;
  // The target for frames while moving from this view on (LiveOptions::frameTimeSeconds);
  // negative: leave it as it is.
  double frameTimeSeconds = -1.0;
};

struct PassInfo {
  uint32_t frame = 0;    // wire frame id, unique per pass
  uint64_t viewId = 0;   // increases with every setView()
  uint64_t viewTag = 0;  // the ViewSettings::tag of the view
  int pass = 0;          // 0: a frame while moving that is not averaged (reduced, or 1 spp)
  FrameScale scale;      // the pass's share of each side of the display (full resolution: 1)
  // The first frame of its view: shown when complete, never mixed with the view before.
  bool firstOfView = false;
  std::shared_ptr<const RenderView> view;  // what the pass renders, at its own resolution
  std::vector<TileRect> tiles;             // in the pass's resolution
  // The light terms its tiles add up (its photon map and gather radius); null: direct only.
  std::shared_ptr<const RenderPass> light;
};

// The photon side of the current view (all zero without photon mapping).
struct PhotonLiveStats {
  CausticMethod method = CausticMethod::None;
  bool noCasters = false;       // caustics are on but no light reaches a caster
  uint64_t photonsPerPass = 0;  // budget: photons emitted per pass
  int passes = 0;               // photon passes traced (or reused) for the current view
  bool reused = false;          // the last is the first view's pass 1, not traced again
  PhotonPassStats last;         // the last photon pass (its map: last.trace.stored photons)
  float radius = 0.0f;          // its gather radius
  // Caustic mapping (method CausticMap):
  int mapResolution = 0;         // texels per side of each light-space view
  int mapViews = 0;              // views over all lights
  bool mapBlur = true;           // the Gaussian blur is on
  double mapBuildSeconds = 0.0;  // rank 0's build of the maps in use
};

// Frame times over the recent frames (every pass counts): what the user sees.
struct FrameTimeStats {
  int frames = 0;                // in the window (up to the last 60)
  double medianSeconds = 0.0;    // a frame's time: its end minus the later of its start and
  double p95Seconds = 0.0;       // the previous frame's end (frames overlap when pipelined)
  double framesPerSecond = 0.0;  // frames / their summed times
  int shownWidth = 0;            // the last finished frame's resolution
  int shownHeight = 0;
  uint64_t fullResolutionFrames = 0;  // frames while moving at full resolution, since the start
  uint64_t reducedFrames = 0;         // and at a reduced one
};

struct LiveStats {
  uint32_t frame = 0;
  uint64_t viewId = 0;
  int pass = 0;
  int passesDone = 0;                  // full-resolution passes finished for the current view
  std::vector<RankStats> ranks;        // index = rank; counts since the viewer started
  double raysPerSecond = 0.0;          // over the last statsInterval
  double lastPassSeconds = 0.0;        // wall time of the last finished full-resolution pass
  double lastPassBusySeconds = 0.0;    // thread-seconds all ranks spent on it
  int totalThreads = 0;                // over all live ranks
  double previewLatencySeconds = 0.0;  // setView() to the view's first frame finished
  double firstFullSeconds = 0.0;       // setView() to its first full-resolution pass finished
  FrameTimeStats frameTimes;
  double frameTimeTargetSeconds = 0.0;
  PhotonLiveStats photons;
};

// Called on the coordinator thread only.
class LiveListener {
 public:
  virtual ~LiveListener() = default;
  virtual void passStarted(const PassInfo& pass) = 0;
  virtual void tileAssigned(uint32_t frame, uint32_t tile, int rank) = 0;
  virtual void tileFinished(uint32_t frame, std::shared_ptr<const TileResult> tile, int rank) = 0;
  virtual void passFinished(uint32_t frame, double seconds) = 0;
  virtual void statsUpdated(const LiveStats& stats) = 0;
};

class LiveRenderer final : private FrameListener {
 public:
  // On the run's dispatcher (master/dispatch/DispatchSession.h), whose scene it renders; it stops
  // the dispatcher when it stops.
  LiveRenderer(WorkDispatcher& dispatcher, const LiveOptions& options);
  // On a dispatcher of its own over cluster (null: this process alone), for a renderer that is
  // the whole run (tests).
  LiveRenderer(const Scene& scene, const LiveOptions& options, Transport* cluster = nullptr);
  ~LiveRenderer() override;
  LiveRenderer(const LiveRenderer&) = delete;
  LiveRenderer& operator=(const LiveRenderer&) = delete;

  // Ends the current frame and starts rendering this view from pass 0.
  void setView(const ViewSettings& view);
  // Makes run() return soon.
  void stop();
  // Renders until stop(). Throws std::runtime_error when a slave reports an error or a render
  // thread fails.
  void run(LiveListener& listener);

  // The numbers statsUpdated reports, now (rays/s: since the last report). Any thread.
  LiveStats stats();

  // The scene's caustic maps with the blur on or off, built on first use (by whichever thread
  // asks first; others wait) and kept until the maps of the other blur setting are built: one
  // set at a time is what the memory check counts. Any thread: the viewer's debug images use
  // them. Throws ResourceLimitError when causticMapsRefusal() says why not.
  std::shared_ptr<const CausticMapEstimator> causticMaps(bool blur);
  // Why the scene's caustic maps would not fit in LiveOptions::memoryLimit; nothing when they do.
  const std::optional<std::string>& causticMapsRefusal() const { return mapsRefusal_; }
  // The scene rank 0 renders with (its kernels' instruction set is the job's).
  const Scene& scene() const { return scene_; }

  // The seed of full-resolution pass p ≥ 1: pass 1 keeps the scene's seed.
  static uint64_t passSeed(uint64_t sceneSeed, int pass);

 private:
  LiveRenderer(std::unique_ptr<WorkDispatcher> own, WorkDispatcher* dispatcher,
               const LiveOptions& options);
  struct Event;
  struct Pass;
  struct PassPlan;

  // FrameListener: the dispatcher's calls, one at a time, without its lock.
  void tileAssigned(uint32_t frame, uint32_t tile, int rank) override;
  void tileFinished(uint32_t frame, TileResult&& tile, int rank) override;
  bool wantsTiles(uint32_t frame) override;

  Pass* findLocked(uint32_t frame);
  std::optional<PassPlan> nextPassLocked();
  // Whether a pass should start now: there is one to render, and no frame running that it
  // must wait for.
  bool mayStartLocked() const;
  void frameFinishedLocked(const Pass& pass, double end);
  // tileFinished's bookkeeping; takes the lock itself (unlike the *Locked functions, which
  // expect it held). Returns whether the coordinator must wake for the tile.
  bool recordFinishedTile(uint32_t frame, TileResult&& tile, int rank);
  // Every pass's news the listener may hear now, in order (the front pass's, and those after it
  // once it has ended).
  void takeDeliveriesLocked(std::vector<Event>& out);
  // The same when newsDueLocked(); then the batch is over.
  void takeDueDeliveriesLocked(std::vector<Event>& out);
  // A tile's news (assigned, finished) was queued: whether the coordinator must wake for it.
  // urgent: it ends a pass, or hands out a pass's last tile (the next may start).
  bool newsQueuedLocked(bool urgent);
  // Whether the news queued should reach the listener now (see kNewsDelay).
  bool newsDueLocked() const;
  // How long the coordinator may sleep before the news queued fall due, at most `bound`.
  double untilNewsDueLocked(double bound) const;
  std::shared_ptr<const RenderPass> passLight(const PassPlan& plan);
  std::shared_ptr<const RenderPass> causticMapLight(const PassPlan& plan);
  PassInfo beginPassLocked(const PassPlan& plan, std::shared_ptr<const RenderPass> light,
                           int liveThreads);
  LiveStats statsLocked(double elapsedSeconds, std::vector<RankStats> ranks);
  double now() const { return secondsSince(start_); }

  std::unique_ptr<WorkDispatcher> ownDispatcher_;  // when it was made without one
  WorkDispatcher& dispatcher_;
  SlaveLink& link_;  // the dispatcher's: the photon passes use it too
  const Scene& scene_;
  LiveOptions options_;
  SteadyClock::time_point start_;

  // Guards what follows. The dispatcher calls this listener holding its delivery lock, which
  // takes this one: never call the dispatcher with this one held.
  std::mutex mutex_;
  std::condition_variable changed_;
  bool stopped_ = false;
  std::optional<ViewSettings> pendingView_;
  SteadyClock::time_point pendingSince_;
  ViewSettings view_;
  uint64_t viewId_ = 0;
  SteadyClock::time_point viewSince_;
  uint32_t nextFrame_ = 1;  // 0 is `prism render`'s frame
  // Passes started whose end the listener has not heard yet, oldest first (two at most: the
  // pipeline's current frame and the next).
  std::deque<std::unique_ptr<Pass>> passes_;
  double newsSince_ = -1.0;  // when the oldest undelivered tile news was queued; -1: none
  bool newsUrgent_ = false;  // news queued that the listener should hear at once
  int lastIndex_ = -1;       // the last pass begun of the current view; -1: none yet
  ResolutionGovernor governor_;
  std::deque<double> frameSeconds_;  // recent frames' times, newest last
  double lastFrameEnd_ = 0.0;        // when the last frame finished (seconds since start_)
  LiveStats live_;
  RayCounters raysAtLastStats_;
  SteadyClock::time_point lastStats_;

  std::atomic<bool> cancelPhotons_{false};  // set by setView() under mutex_

  // Coordinator thread only: the photon side.
  std::unique_ptr<PhotonTracer> tracer_;  // planned for tracerBudget_ photons per pass
  uint64_t tracerBudget_ = 0;
  float maxRadius_;
  PhotonGatherSettings gather_;  // the last photon pass's gather, for the next one's
  // Pass 1's photons as first traced, with rank 0's estimator (radii and discs) and the pass's
  // statistics, for every later view's pass 1 with the same photon budget.
  struct FirstPhotonPass {
    uint64_t budget = 0;
    uint32_t frame = 0;  // the pass it was traced for, as the slaves keep it
    std::shared_ptr<const PhotonMap> map;
    std::shared_ptr<const PhotonGather> estimator;
    PhotonPassStats stats;
  };
  std::optional<FirstPhotonPass> firstPhotonPass_;

  std::optional<std::string> mapsRefusal_;
  std::mutex mapsMutex_;  // guards the two below; mutex_ is never taken while holding it
  std::map<bool, std::shared_ptr<const CausticMapEstimator>> causticMaps_;
  std::map<bool, double> mapBuildSeconds_;
};

}  // namespace prism

// The run's one work dispatcher: the lease-managed queue of all distributed work. It hands the
// tiles of frames to rank 0's render threads and to the slaves, and a photon pass's shares
// (photons to trace, radii to find: runShares, master/dispatch/ShareWork.h) to the ranks, and
// takes in what comes back, the same way for both: every piece is leased to its rank in a
// TileScheduler, re-issued when its slave is retired, and accepted once. `prism render`,
// `speedup` and `sweep` run one frame on it at a time (master/frame/FrameRenderer.h), the
// viewer a stream of frames (master/live/LiveRenderer.h); one dispatcher lives as long as
// the run (master/dispatch/DispatchSession.h). It owns the run's SlaveLink, whose roster is the
// one record of every rank, and rank 0's render threads, started once and fed every frame.
//
// Tiles: it keeps every live slave supplied with `prefetch` tiles per render thread (a View
// message first when the frame has a view of its own) and routes the slaves' messages (through
// SlaveLink, so status means the same everywhere): a TileResult is checked against the plan and
// accepted once; a late or duplicate one, or one of a frame already ended, is counted stale and
// dropped; a heartbeat naming the frame re-issues the tiles its slave lost. A share's answer
// goes to the shares being done (a late one, of a pass done without it, is dropped), and a late
// Echo (of a link probe that gave up on it) is ignored. Silent slaves (SlaveLink::retireSilent)
// and slaves past their lease are retired and their work re-issued at once.
//
// Threads: service() and runShares() are called by one coordinating thread, the only one that
// talks to the slaves, which calls beginFrame too; rank 0's render threads take tiles
// concurrently; endFrame, stop and stats may be called from any thread. Listeners hear of tiles
// after the dispatcher's lock is released (FrameListener).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "cluster/DistributionOptions.h"
#include "cluster/TileWorkerPool.h"
#include "master/dispatch/GeometryShare.h"
#include "master/dispatch/ShareWork.h"
#include "master/dispatch/SlaveLink.h"
#include "master/dispatch/TileScheduler.h"
#include "render/RenderPass.h"
#include "render/RenderView.h"
#include "render/Tile.h"
#include "scene/Scene.h"

namespace prism {

// What one frame renders and who may render it.
struct FramePlan {
  // Tags the frame's messages; every frame of a run needs its own, so that a late tile or
  // heartbeat of an earlier frame is recognised.
  uint32_t frame = 0;
  std::vector<TileRect> tiles;
  // Null: the scene's own camera and settings (`prism render`); else the viewer's view, sent to
  // each slave before its first tile of the frame.
  std::shared_ptr<const RenderView> view;
  std::shared_ptr<const RenderPass> light;  // the light terms; null: direct light only
  // `prism speedup` measures with part of the cluster: rank 0's threads may render nothing, and
  // only slaves 1..activeSlaves get tiles (-1: every slave).
  bool masterRenders = true;
  int activeSlaves = -1;
  Schedule schedule = Schedule::Dynamic;
};

// Told about the current frame's tiles, from the coordinating thread or a render thread, one
// call at a time and in the order the dispatcher decided them (a tile is told assigned before it
// is told finished), but without the dispatcher's lock: a listener may call the dispatcher
// (endFrame, tilesDone, ...). It hears nothing of a frame once endFrame(frame) has returned, so
// it may be destroyed then.
class FrameListener {
 public:
  virtual ~FrameListener() = default;
  virtual void tileAssigned(uint32_t /*frame*/, uint32_t /*tile*/, int /*rank*/) {}
  // Whether the frame's tiles are still wanted: the viewer drops a pass a moment before it ends
  // its frame here, and a tile arriving in between is stale like one of an ended frame.
  virtual bool wantsTiles(uint32_t /*frame*/) { return true; }
  // A tile of the frame, accepted: the first copy, matching the plan. The coordinating thread
  // is woken for the frame's last tile only; a listener that wants it sooner wakes it.
  virtual void tileFinished(uint32_t frame, TileResult&& tile, int rank) = 0;
};

class WorkDispatcher {
 public:
  // cluster null (or of one rank): rank 0's threads alone.
  WorkDispatcher(const Scene& scene, Transport* cluster, const DistributionOptions& options);
  ~WorkDispatcher();  // stops and joins the render threads
  WorkDispatcher(const WorkDispatcher&) = delete;
  WorkDispatcher& operator=(const WorkDispatcher&) = delete;

  const Scene& scene() const { return scene_; }
  SlaveLink& link() { return link_; }
  // Rank 0's threads, resolved here once from options.threads (util/ThreadCount.h): they render
  // its tiles, and its photon passes and caustic maps are made with as many.
  int localThreads() const { return pool_.threadCount(); }
  // Live ranks' render threads (a slave's from its Ready, else rank 0's count in its place).
  int liveThreads();

  // Starts rank 0's render threads, once a run (later calls do nothing); they take tiles of
  // whatever frame is current.
  void startLocalWorkers();
  // Rank 0's built geometry is broadcast by the coordinating thread before it first talks to
  // the slaves (the opening): the first frame's tiles go to rank 0's render threads first, so
  // they render while it is sent, and the slaves get theirs after (not before a photon pass: no
  // tiles then). Once a run; set before any frame. `record` (which must outlive the opening)
  // is told what was sent (broadcastGeometry, master/dispatch/GeometryShare.h).
  void sendGeometryAtOpening(GeometrySharePlan& record) { geometryRecord_ = &record; }
  // Whether the opening has not run yet (no frame or pass began): the slaves still wait for it.
  bool openingPending() const { return geometryRecord_ != nullptr; }
  // Makes plan the current frame; every one before is ended (its tiles left are dropped, its
  // late results are stale). Called by the coordinating thread: it sends the slaves their first
  // jobs before rank 0's render threads take any tile (after them, when the opening runs here).
  // The listener must live until endFrame(plan.frame) returns.
  void beginFrame(FramePlan plan, FrameListener* listener);
  // Pipelining (the viewer's frame stream): adds plan as the current frame behind the frames
  // still running, which are not ended. A render thread or slave takes the oldest frame's tiles
  // first and the next frame's once the older ones have none left for it, so nobody waits for
  // a round trip between frames. An older frame leaves once complete (or ended).
  void queueFrame(FramePlan plan, FrameListener* listener);
  // Ends `frame` now if it is still running: no more of its tiles are handed out. Frames begun
  // since are left alone, so a caller on another thread cannot end a newer frame by mistake.
  // Returns once its listener has heard every tile accepted (no call to it is left, nor under
  // way on another thread).
  void endFrame(uint32_t frame);
  // Whether the current (newest) frame has all its tiles (false with no frame).
  bool frameComplete();
  size_t tilesDone();

  // One step of the coordinating thread: feeds the slaves, waits up to waitSeconds for a
  // message or a change here (a frame finished on this rank, stop(), wake()), routes every
  // message that has arrived, and retires silent slaves and expired leases. Throws
  // std::runtime_error when a slave reports an error or sends what it must not.
  void service(double waitSeconds);
  // Ends a service() wait in progress, or the next one (another thread has news for the
  // coordinating one); safe from any thread.
  void wake();

  // The shares of pass `pass` (master/dispatch/ShareWork.h), on the coordinating thread, which
  // serves the slaves meanwhile as service() does (tiles of running frames included): each
  // slave is sent its share, rank 0 does its own (then any re-issued to it) with work.doHere,
  // and true is returned once every share is accepted. Once *cancel is set, the slaves still
  // holding a share are told to stop (PhotonCancel, they send nothing for it), rank 0's work
  // in progress is waited for (it watches cancel too), and false is returned.
  bool runShares(uint32_t pass, const std::vector<ShareRange>& shares, ShareWork& work,
                 const std::atomic<bool>* cancel = nullptr);

  // Render threads stop after their current tile; cancel() abandons that tile too (no result).
  void stop();
  void cancel();
  // Waits for the render threads; rethrows the first exception one hit.
  void join();
  bool localFailed() { return pool_.failed(); }

  // Per rank, since the run began: the roster (SlaveLink::roster).
  std::vector<RankStats> stats() { return link_.roster(); }
  size_t reissuedTiles();

 private:
  struct Frame;
  struct ShareBatch;
  // A tile's news for a listener: assigned, or finished (with its result).
  struct News {
    FrameListener* listener;
    uint32_t frame;
    uint32_t tile;
    int rank;
    std::optional<TileResult> finished;
  };

  Frame* findLocked(uint32_t frame);
  void addFrame(FramePlan plan, FrameListener* listener, bool endEarlier);
  std::optional<TileJob> nextLocalJob();
  void accept(uint32_t frame, TileResult&& tile, int rank);
  // Whether the frame's listener still wants its tiles, asked without mutex_.
  bool listenerWants(uint32_t frame);
  // Tells the listeners the news queued, in order, one call at a time; returns once the queue is
  // empty (another thread may have told some). Called without mutex_.
  void deliverNews();
  void feedSlaves();
  // Up to its prefetch, the next jobs for a slave (oldest frame first), encoded (mutex_ held);
  // their assignments are queued as news.
  std::vector<std::vector<uint8_t>> jobsForLocked(int rank);
  // Sends them; a refused send retires the slave.
  void sendJobs(int rank, std::vector<std::vector<uint8_t>>& jobs);
  void route(const SlaveMessage& message);
  void routeShare(const SlaveMessage& message);
  void sendShares(ShareBatch& batch);
  void cancelShares(ShareBatch& batch);
  void retireRank(int rank);
  void runOpening(bool rank0Renders);
  double now() const { return secondsSince(start_); }

  const Scene& scene_;
  DistributionOptions options_;
  SlaveLink link_;
  TileWorkerPool pool_;
  SteadyClock::time_point start_;
  GeometrySharePlan* geometryRecord_ = nullptr;  // the opening, pending; coordinating thread only

  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<std::unique_ptr<Frame>> frames_;  // running, oldest first; the last is current
  std::unique_ptr<ShareBatch> shares_;          // the photon pass's shares being done, if any
  size_t reissuedBefore_ = 0;                   // by frames already ended
  bool stopped_ = false;
  std::deque<News> news_;  // for the listeners, in the order decided; guarded by mutex_
  // Held while a listener is called (taken before mutex_, never while holding it), so calls come
  // one at a time in order; recursive, since a listener may call what delivers news.
  std::recursive_mutex delivering_;
};

}  // namespace prism

#include "master/analysis/TileScheduleSimulator.h"

#include <algorithm>
#include <deque>
#include <optional>
#include <queue>
#include <stdexcept>

namespace prism {
namespace {

enum class EventKind {
  JobArrives,      // a tile job reaches its worker
  TileRendered,    // a worker thread finished a tile
  ResultAtMaster,  // a result's first byte reaches the master's link
  ResultReceived   // the whole result is in: the master refills that worker
};

struct Event {
  double time = 0.0;
  size_t order = 0;  // scheduling order: breaks ties deterministically
  EventKind kind = EventKind::JobArrives;
  int worker = 0;
  uint32_t tile = 0;
};

struct Later {
  bool operator()(const Event& a, const Event& b) const {
    return a.time != b.time ? a.time > b.time : a.order > b.order;
  }
};

class Simulation {
 public:
  explicit Simulation(const ScheduleSimulation& s)
      : s_(s),
        workers_(static_cast<size_t>(s.workers)),
        result_{0.0, std::vector<double>(static_cast<size_t>(s.workers), 0.0),
                std::vector<size_t>(static_cast<size_t>(s.workers), 0)} {
    for (uint32_t tile = 0; tile < s.tileSeconds.size(); ++tile) {
      if (s.schedule == Schedule::Static) {
        workers_[tile % workers_.size()].own.push_back(tile);
      } else {
        shared_.push_back(tile);
      }
    }
    for (Worker& w : workers_) w.freeThreads = s.threadsPerWorker;
  }

  SimulatedFrame run() {
    for (int w = 0; w < s_.workers; ++w) refill(w, 0.0);
    while (!events_.empty()) {
      const Event e = events_.top();
      events_.pop();
      handle(e);
    }
    return result_;
  }

 private:
  struct Worker {
    std::deque<uint32_t> own;     // static schedule
    std::deque<uint32_t> queued;  // arrived, waiting for a thread
    int freeThreads = 0;
    int inFlight = 0;  // sent by the master, result not yet received
  };

  void schedule(double time, EventKind kind, int worker, uint32_t tile) {
    events_.push({time, nextOrder_++, kind, worker, tile});
  }

  double transferSeconds(double bytes) const { return bytes / s_.link.bytesPerSecond; }

  std::optional<uint32_t> nextTileFor(int worker) {
    for (std::deque<uint32_t>* queue : {&workers_[worker].own, &shared_}) {
      if (!queue->empty()) {
        const uint32_t tile = queue->front();
        queue->pop_front();
        return tile;
      }
    }
    return std::nullopt;
  }

  // The master tops the worker up to `prefetch` jobs in flight; its sends leave one by one.
  void refill(int worker, double now) {
    Worker& w = workers_[worker];
    while (w.inFlight < s_.prefetch) {
      const std::optional<uint32_t> tile = nextTileFor(worker);
      if (!tile) return;
      ++w.inFlight;
      egressFree_ = std::max(egressFree_, now) + transferSeconds(s_.jobBytes);
      schedule(egressFree_ + s_.link.latencySeconds, EventKind::JobArrives, worker, *tile);
    }
  }

  void startTiles(int worker, double now) {
    Worker& w = workers_[worker];
    while (w.freeThreads > 0 && !w.queued.empty()) {
      const uint32_t tile = w.queued.front();
      w.queued.pop_front();
      --w.freeThreads;
      const double seconds = s_.tileSeconds[tile] / s_.cpuShare;
      result_.busySeconds[worker] += seconds;
      ++result_.tilesByWorker[worker];
      schedule(now + seconds, EventKind::TileRendered, worker, tile);
    }
  }

  void handle(const Event& e) {
    Worker& w = workers_[e.worker];
    switch (e.kind) {
      case EventKind::JobArrives:
        w.queued.push_back(e.tile);
        startTiles(e.worker, e.time);
        break;
      case EventKind::TileRendered:
        ++w.freeThreads;
        schedule(e.time + s_.link.latencySeconds, EventKind::ResultAtMaster, e.worker, e.tile);
        startTiles(e.worker, e.time);
        break;
      case EventKind::ResultAtMaster: {
        // Events come in time order, so results queue on the master's link first come first.
        const double bytes = s_.resultBytes.empty() ? 0.0 : s_.resultBytes[e.tile];
        ingressFree_ = std::max(ingressFree_, e.time) + transferSeconds(bytes);
        schedule(ingressFree_, EventKind::ResultReceived, e.worker, e.tile);
        break;
      }
      case EventKind::ResultReceived:
        --w.inFlight;
        result_.seconds = std::max(result_.seconds, e.time);
        refill(e.worker, e.time);
        break;
    }
  }

  const ScheduleSimulation& s_;
  std::vector<Worker> workers_;
  std::deque<uint32_t> shared_;
  std::priority_queue<Event, std::vector<Event>, Later> events_;
  size_t nextOrder_ = 0;
  double egressFree_ = 0.0;
  double ingressFree_ = 0.0;
  SimulatedFrame result_;
};

}  // namespace

SimulatedFrame simulateTileSchedule(const ScheduleSimulation& simulation) {
  if (simulation.workers < 1 || simulation.threadsPerWorker < 1 || simulation.prefetch < 1) {
    throw std::invalid_argument("simulateTileSchedule: workers, threads and prefetch must be >= 1");
  }
  if (!(simulation.cpuShare > 0.0 && simulation.cpuShare <= 1.0)) {
    throw std::invalid_argument("simulateTileSchedule: cpuShare must lie in (0, 1]");
  }
  if (!simulation.resultBytes.empty() &&
      simulation.resultBytes.size() != simulation.tileSeconds.size()) {
    throw std::invalid_argument("simulateTileSchedule: one result size per tile needed");
  }
  return Simulation(simulation).run();
}

}  // namespace prism

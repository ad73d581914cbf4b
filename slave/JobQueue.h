// Tile jobs received from the master, waiting for this rank's render threads.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>

#include "cluster/TileWorkerPool.h"

namespace prism {

class JobQueue {
 public:
  void push(const TileJob& job) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      jobs_.push_back(job);
    }
    ready_.notify_one();
  }

  // Blocks until a job arrives; returns nothing once the queue is closed and empty.
  std::optional<TileJob> pop() {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait(lock, [this] { return closed_ || !jobs_.empty(); });
    if (jobs_.empty()) return std::nullopt;
    const TileJob job = jobs_.front();
    jobs_.pop_front();
    return job;
  }

  // Wakes every waiting thread; jobs already queued are still handed out.
  void close() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
    }
    ready_.notify_all();
  }

  // Drops the jobs not yet started (the master has ended the frame).
  void clear() {
    const std::lock_guard<std::mutex> lock(mutex_);
    jobs_.clear();
  }

  // Drops the jobs not yet started of frames before `frame` (the master has ended them).
  void dropBefore(uint32_t frame) {
    const std::lock_guard<std::mutex> lock(mutex_);
    jobs_.erase(std::remove_if(jobs_.begin(), jobs_.end(),
                               [frame](const TileJob& job) { return job.frame < frame; }),
                jobs_.end());
  }

 private:
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<TileJob> jobs_;
  bool closed_ = false;
};

}  // namespace prism

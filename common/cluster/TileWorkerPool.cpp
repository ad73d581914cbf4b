#include "cluster/TileWorkerPool.h"

#include "render/TileRenderer.h"
#include "util/Parallel.h"

namespace prism {

TileWorkerPool::TileWorkerPool(const Scene& scene, ThreadCount threads)
    : scene_(scene), threadCount_(threads.value()) {}

TileWorkerPool::~TileWorkerPool() {
  for (std::thread& t : threads_) {
    if (t.joinable()) t.join();
  }
}

void TileWorkerPool::start(JobSource source, ResultHandler onResult) {
  start(std::move(source),
        [onResult](const TileJob&, TileResult&& tile) { onResult(std::move(tile)); });
}

namespace {
std::atomic<uint64_t> poolsStarted{0};
}  // namespace

uint64_t TileWorkerPool::startedInProcess() {
  return poolsStarted.load();
}

void TileWorkerPool::start(JobSource source, JobResultHandler onResult) {
  ++poolsStarted;
  threads_.reserve(static_cast<size_t>(threadCount_));
  for (int t = 0; t < threadCount_; ++t) {
    threads_.emplace_back([this, source, onResult] {
      try {
        while (const std::optional<TileJob> job = source()) {
          // A renderer is a camera and a few numbers: cheap to make per tile.
          const LightTerms terms = job->pass ? job->pass->terms() : LightTerms{};
          const TileRenderer renderer =
              job->view ? TileRenderer(scene_, *job->view, terms) : TileRenderer(scene_, terms);
          const std::atomic<bool>* frameEnded = job->frameEnded.get();
          TileResult tile = renderer.render(job->tileIndex, job->rect, &cancelled_, frameEnded);
          if (cancelled_) break;                    // possibly incomplete
          if (frameEnded && *frameEnded) continue;  // nobody wants it, and possibly incomplete
          onResult(*job, std::move(tile));
        }
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failureMutex_);
        if (!failure_) failure_ = std::current_exception();
      }
    });
  }
}

bool TileWorkerPool::failed() {
  const std::lock_guard<std::mutex> lock(failureMutex_);
  return failure_ != nullptr;
}

void TileWorkerPool::join() {
  for (std::thread& t : threads_) {
    if (t.joinable()) t.join();
  }
  threads_.clear();
  if (failure_) std::rethrow_exception(failure_);
}

}  // namespace prism

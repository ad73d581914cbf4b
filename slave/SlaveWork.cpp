#include "slave/SlaveWork.h"

#include <utility>

namespace prism {

SlaveWork::SlaveWork(Transport& transport_, std::unique_ptr<const Scene> scene_,
                     ThreadCount threads, const MemoryLimit& memoryLimit)
    : transport(transport_),
      scene(std::move(scene_)),
      outbox(transport_),
      photons(*scene, threads.value(), transport_, memoryLimit),
      pool(*scene, threads),
      heartbeat(transport_, shared, frames) {
  pool.start([this] { return jobs.pop(); },
             [this](const TileJob& job, TileResult&& tile) {
               outbox.add(job.frame, std::move(tile), job.view ? job.view->displayExposure : 0.0f);
             });
}

SlaveWork::~SlaveWork() {
  if (loopLock.owns_lock()) loopLock.unlock();
  heartbeat.stop();
  jobs.clear();
  jobs.close();
  pool.cancel();  // ~TileWorkerPool joins its threads; photons' futures wait for theirs
}

void SlaveWork::stop() {
  heartbeat.stop();
  jobs.clear();
  jobs.close();
  pool.cancel();  // nobody will take a tile still being rendered: stop it after its row
  photons.wait();
  pool.join();
}

}  // namespace prism

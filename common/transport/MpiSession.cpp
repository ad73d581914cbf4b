#include "transport/MpiSession.h"

#include <mpi.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <string>
#include <thread>

#include "transport/LoopbackNoDelay.h"
#include "util/HugePages.h"
#include "util/Stopwatch.h"

namespace prism {
namespace {

constexpr int kMessageTag = 7;
// A waiting rank probes MPI at least this often, rung or not. Each probe runs MPI's progress
// engine (a large message needs both sides' progress). A millisecond keeps a waiting rank from
// taking measurable time from the render threads on its core. Sleeping until rung alone was
// measured and not kept: under other load on the machine the ranks then got a smaller share
// of the cores (a 2-rank render 3.6-4.2 s instead of 2.8-3.0 s beside two busy loops;
// docs/distributed.md, "Waiting for messages").
constexpr double kProbeIntervalSeconds = 0.001;

using Clock = SteadyClock;

// MPI_Finalize takes well under a second here, a few under load; ten means it will not return.
constexpr double kFinalizeBoundSeconds = 10.0;

// How a wait polls: sleeping between tests keeps a waiting rank from burning the core its render
// threads (or rank 0's build) need; spinning keeps a transfer under way moving, since Open MPI
// moves a nonblocking collective's data only inside its calls.
enum class Polling { Sleep, Spin };

// Polls a request until it completes or the time is up.
bool waitBounded(MPI_Request& request, double timeoutSeconds, Polling polling = Polling::Sleep) {
  const auto start = Clock::now();
  for (;;) {
    int done = 0;
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return true;
    if (secondsSince(start) > timeoutSeconds) return false;
    if (polling == Polling::Spin) {
      std::this_thread::yield();
    } else {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }
}

// Left to choose its point-to-point layer, Open MPI opens and probes every candidate (UCX, cm,
// ob1), which adds about 0.2 s to every job's start; on one node ob1's shared-memory transport
// carries Prism's messages as well (docs/distributed.md, measured). So when mpirun says every rank
// is on this node and the user chose no layer (an OMPI_MCA_pml of their own, or mpirun's --mca pml,
// wins), use ob1. Other launchers (srun) do not say, and keep Open MPI's default.
void preferSharedMemoryOnOneNode() {
  const char* size = std::getenv("OMPI_COMM_WORLD_SIZE");
  const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
  if (!size || !local || std::string(size) != local) return;
  ::setenv("OMPI_MCA_pml", "ob1", /*overwrite=*/0);
}

}  // namespace

struct MpiSession::PendingSend {
  int dest = 0;
  std::vector<uint8_t> bytes;
  MPI_Request request = MPI_REQUEST_NULL;
};

MpiSession::MpiSession(int* argc, char*** argv) {
  preferSharedMemoryOnOneNode();
  int provided = 0;
  // SERIALIZED rather than FUNNELED: `prism view` keeps MPI in one coordinator thread that is
  // not the main one (the main thread runs the Qt event loop). Calls are never concurrent.
  const auto initStart = Clock::now();
  MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided);
  initSeconds_ = secondsSince(initStart);
  // MPI_Init opened the connection to the launcher's PMIx server; without this, MPI_Finalize
  // stalls 40 ms on Nagle's algorithm (LoopbackNoDelay.h).
  disableNagleOnLoopbackConnections();
  if (provided < MPI_THREAD_SERIALIZED) {
    MPI_Finalize();
    throw TransportError("the MPI library does not allow threads (MPI_THREAD_SERIALIZED)");
  }
  // Errors come back as codes so they can be reported, not as an immediate abort.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  setUpDoorbells();
}

// Each rank binds a doorbell named after the job and its rank; the ranks on one machine learn
// each other's names and ring them, provided every bell on the machine bound. Ranks on other
// machines cannot ring: their messages are found by the probe every millisecond.
void MpiSession::setUpDoorbells() {
  peerDoorbells_.assign(static_cast<size_t>(size_), std::string());
  MPI_Comm node = MPI_COMM_NULL;
  if (MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node) !=
      MPI_SUCCESS) {
    doorbell_ = std::make_unique<Doorbell>();
    return;
  }
  int nodeRank = 0;
  int nodeSize = 1;
  MPI_Comm_rank(node, &nodeRank);
  MPI_Comm_size(node, &nodeSize);
  // The job's name on this machine, from its first rank here: unique while that process lives.
  char job[64] = {};
  if (nodeRank == 0) {
    std::snprintf(job, sizeof job, "prism-%ld-%lld", static_cast<long>(::getpid()),
                  static_cast<long long>(Clock::now().time_since_epoch().count()));
  }
  MPI_Bcast(job, sizeof job, MPI_CHAR, 0, node);
  const auto bellName = [&job](int rank) { return std::string(job) + "-" + std::to_string(rank); };
  doorbell_ = std::make_unique<Doorbell>(bellName(rank_));
  int bound = doorbell_->reachable() ? 1 : 0;
  int everyBound = 0;
  MPI_Allreduce(&bound, &everyBound, 1, MPI_INT, MPI_MIN, node);
  std::vector<int> ranksHere(static_cast<size_t>(nodeSize));
  MPI_Allgather(&rank_, 1, MPI_INT, ranksHere.data(), 1, MPI_INT, node);
  MPI_Comm_free(&node);
  if (!everyBound) return;
  for (int r : ranksHere) {
    if (r != rank_) peerDoorbells_[static_cast<size_t>(r)] = bellName(r);
  }
  rungByPeers_ = rank_ == 0 ? nodeSize == size_ : !peerDoorbells_[0].empty();
}

bool MpiSession::ring(int dest) const {
  const std::string& bell = peerDoorbells_[static_cast<size_t>(dest)];
  return bell.empty() || doorbell_->ring(bell);
}

MpiSession::~MpiSession() {
  const auto start = Clock::now();
  while (progressSends() > 0 && secondsSince(start) < 10.0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  // Sends to a rank that stopped answering can never complete; cancel them so MPI can finish.
  for (auto& pending : pendingSends_) {
    MPI_Cancel(&pending->request);
    MPI_Request_free(&pending->request);
  }
  pendingSends_.clear();
  finalizeBounded();
}

// MPI_Finalize waits for every rank of the job. Under --enable-recovery a rank can die and the job
// go on; then Finalize may wait for it for good (seen: two live ranks stuck in its fence after a
// third crashed), even when rank 0 ends the job with MPI_Abort, whose kill does not always reach
// a rank. The work is done and delivered by now, so past a bound the process ends without it.
void MpiSession::finalizeBounded() {
  std::mutex mutex;
  std::condition_variable done;
  bool finished = false;
  std::thread watchdog([&] {
    std::unique_lock<std::mutex> lock(mutex);
    if (done.wait_for(lock, std::chrono::duration<double>(kFinalizeBoundSeconds),
                      [&] { return finished; })) {
      return;
    }
    std::fprintf(stderr,
                 "prism: rank %d: MPI_Finalize did not return within %.0f s (a rank of the job is "
                 "gone); ending without it\n",
                 rank_, kFinalizeBoundSeconds);
    std::fflush(nullptr);
    std::_Exit(1);
  });
  MPI_Finalize();
  {
    const std::lock_guard<std::mutex> lock(mutex);
    finished = true;
  }
  done.notify_all();
  watchdog.join();
}

void MpiSession::broadcast(std::vector<uint8_t>& bytes, double timeoutSeconds) {
  uint64_t size = bytes.size();
  MPI_Request request;
  MPI_Ibcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD, &request);
  if (!waitBounded(request, timeoutSeconds)) {
    throw TransportError("no scene from rank 0 within " + std::to_string(timeoutSeconds) + " s");
  }
  // A fresh buffer on 2 MiB pages: in 4 KiB pages the receiving ranks' first touch of a 300 MB
  // geometry took 3-4 s of page faults on a virtual machine, 0.2 s once the pages existed.
  if (bytes.capacity() < size) {
    std::vector<uint8_t>().swap(bytes);
    reserveOnHugePages(bytes, size);
  }
  bytes.resize(size);
  // The size came, so rank 0 is sending now: spin. With the 0.2 ms sleeps between tests, 86 MB
  // took 1-2 s over shared memory (docs/distributed.md, "One build per job"). MPI counts are
  // ints: send large descriptions in chunks.
  constexpr uint64_t kChunk = 1u << 30;
  for (uint64_t offset = 0; offset < size; offset += kChunk) {
    const int count = static_cast<int>(std::min(kChunk, size - offset));
    MPI_Ibcast(bytes.data() + offset, count, MPI_BYTE, 0, MPI_COMM_WORLD, &request);
    if (!waitBounded(request, timeoutSeconds, Polling::Spin)) {
      throw TransportError("scene broadcast stalled for " + std::to_string(timeoutSeconds) + " s");
    }
  }
}

int MpiSession::ranksOnThisNode() const {
  // Open MPI's launcher says; Slurm's srun says SLURM_NTASKS_PER_NODE only for even layouts.
  for (const char* name : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS"}) {
    if (const char* value = std::getenv(name)) {
      const int n = std::atoi(value);
      if (n >= 1) return n;
    }
  }
  return 1;
}

bool MpiSession::send(int dest, std::vector<uint8_t> bytes) {
  if (bytes.size() > static_cast<size_t>(std::numeric_limits<int>::max())) {
    throw TransportError("message of " + std::to_string(bytes.size()) + " bytes is too large");
  }
  auto pending = std::make_unique<PendingSend>();
  pending->dest = dest;
  pending->bytes = std::move(bytes);
  const int error = MPI_Isend(pending->bytes.data(), static_cast<int>(pending->bytes.size()),
                              MPI_BYTE, dest, kMessageTag, MPI_COMM_WORLD, &pending->request);
  if (error != MPI_SUCCESS) return false;
  // One test pushes out what MPI can send at once (a small message), so the ring below rarely
  // comes before the message; what is left completes in progressSends(), which rings again.
  int done = 0;
  MPI_Test(&pending->request, &done, MPI_STATUS_IGNORE);
  // A peer on this machine whose bell no longer answers has ended. Open MPI may never fail a
  // send to it (under --enable-recovery a send to a dead rank over TCP stays pending), so the
  // bell is what tells the caller; a slave whose rank 0 is gone must not wait for it.
  if (!ring(dest)) {
    if (!done) {
      MPI_Cancel(&pending->request);
      MPI_Request_free(&pending->request);
    }
    return false;
  }
  if (!done) pendingSends_.push_back(std::move(pending));
  return true;
}

size_t MpiSession::progressSends() {
  for (auto it = pendingSends_.begin(); it != pendingSends_.end();) {
    int done = 0;
    MPI_Test(&(*it)->request, &done, MPI_STATUS_IGNORE);
    if (!done) {
      ++it;
      continue;
    }
    // A message MPI could not hand over at once (a full queue) went out only now: ring again,
    // or its receiver, woken too early, sleeps on.
    ring((*it)->dest);
    it = pendingSends_.erase(it);
  }
  return pendingSends_.size();
}

std::optional<IncomingMessage> MpiSession::poll() {
  progressSends();
  int arrived = 0;
  MPI_Status status;
  MPI_Iprobe(MPI_ANY_SOURCE, kMessageTag, MPI_COMM_WORLD, &arrived, &status);
  // Open MPI's probe matches first and runs the progress engine after: a message that reached
  // this rank's queue only now is seen by a second probe. (Probing every millisecond hid this;
  // a rank woken by a ring must see the message the ring announced.)
  if (!arrived) MPI_Iprobe(MPI_ANY_SOURCE, kMessageTag, MPI_COMM_WORLD, &arrived, &status);
  if (!arrived) return std::nullopt;
  int count = 0;
  MPI_Get_count(&status, MPI_BYTE, &count);
  IncomingMessage message;
  message.source = status.MPI_SOURCE;
  message.bytes.resize(static_cast<size_t>(std::max(count, 0)));
  if (MPI_Recv(message.bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, kMessageTag,
               MPI_COMM_WORLD, MPI_STATUS_IGNORE) != MPI_SUCCESS) {
    throw TransportError("receiving from rank " + std::to_string(status.MPI_SOURCE) + " failed");
  }
  return message;
}

std::optional<IncomingMessage> MpiSession::waitForMessage(double timeoutSeconds) {
  const auto start = Clock::now();
  for (;;) {
    if (auto message = poll()) return message;
    const double left = timeoutSeconds - secondsSince(start);
    if (left <= 0.0) return std::nullopt;
    if (sleepFor(left) == Doorbell::Heard::Self) return poll();  // woken: what came, or nothing
  }
}

void MpiSession::awaitActivity(double timeoutSeconds) {
  sleepFor(timeoutSeconds);
}

Doorbell::Heard MpiSession::sleepFor(double seconds) {
  // A ring (a peer's message, or wake()) ends the sleep at once: no message waits for the
  // probe interval where peers can ring.
  return doorbell_->wait(std::min(seconds, kProbeIntervalSeconds));
}

void MpiSession::wake() {
  doorbell_->ringSelf();
}

void MpiSession::abortJob(int exitCode) {
  MPI_Abort(MPI_COMM_WORLD, exitCode);
  std::_Exit(exitCode);  // MPI_Abort does not return; this keeps [[noreturn]] honest
}

}  // namespace prism

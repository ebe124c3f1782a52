#pragma once
// Independent jobs on several threads at once. Used for CRM runs on a GPU: one small run (a wheel,
// an annulus) keeps only a fraction of the device busy, since each step is a chain of short kernels
// with a host round trip between stages; several runs, each on its own host thread and therefore on
// its own CUDA stream, fill each other's gaps. WorkerPool serves short jobs called again and again (the
// calibrator's wheel slips, tens of microseconds each), where starting threads per call would cost
// more than the jobs.
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace terracal {

// Calls job(i) for every i in [0, n), on up to `width` threads at once, and returns when all have
// ended. width <= 1 (or n <= 1): in order, on the calling thread, exactly as a plain loop. A job that
// throws stops the hand-out of later jobs; once the running ones have ended, the exception of the
// lowest failed index is rethrown, so that a failure reads the same as in the plain loop.
void run_concurrently(std::size_t n, int width, const std::function<void(std::size_t)>& job);

struct Handout;  // the jobs of one call (concurrent_jobs.cpp)

// run_concurrently's contract on threads that stay: `width` - 1 of them wait between calls, and the
// calling thread takes part. One call at a time (the pool belongs to the thread that calls it).
class WorkerPool {
 public:
  explicit WorkerPool(int width);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;
  int width() const { return static_cast<int>(workers_.size()) + 1; }
  void run(std::size_t n, const std::function<void(std::size_t)>& job);

 private:
  void serve();
  std::vector<std::thread> workers_;
  std::mutex m_;
  std::condition_variable wake_, done_;
  std::size_t generation_ = 0;  // one per call of run
  int busy_ = 0;                // workers still on this call's jobs
  bool stop_ = false;
  Handout* handout_ = nullptr;
};

}  // namespace terracal

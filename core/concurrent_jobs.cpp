#include "core/concurrent_jobs.hpp"

#include <algorithm>
#include <atomic>
#include <exception>

namespace terracal {

// The jobs of one call, handed out one index at a time to every thread that works on it.
struct Handout {
  std::size_t n;
  const std::function<void(std::size_t)>& job;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex m;
  std::size_t first_failure;
  std::exception_ptr error;

  Handout(std::size_t count, const std::function<void(std::size_t)>& j) : n(count), job(j), first_failure(count) {}
  void work() {
    for (;;) {
      if (failed.load()) return;
      const std::size_t i = next.fetch_add(1);
      if (i >= n) return;
      try {
        job(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(m);
        if (i < first_failure) first_failure = i, error = std::current_exception();
        failed = true;
      }
    }
  }
  void rethrow() const {
    if (error) std::rethrow_exception(error);
  }
};

void run_concurrently(std::size_t n, int width, const std::function<void(std::size_t)>& job) {
  if (width <= 1 || n <= 1) {
    for (std::size_t i = 0; i < n; ++i) job(i);
    return;
  }
  Handout h(n, job);
  const std::size_t threads = std::min<std::size_t>(n, std::size_t(width));
  std::vector<std::thread> pool;
  pool.reserve(threads);
  for (std::size_t t = 0; t < threads; ++t) pool.emplace_back([&h] { h.work(); });
  for (auto& t : pool) t.join();
  h.rethrow();
}

WorkerPool::WorkerPool(int width) {
  for (int t = 1; t < width; ++t) workers_.emplace_back([this] { serve(); });
}

WorkerPool::~WorkerPool() {
  {
    const std::lock_guard<std::mutex> lock(m_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

void WorkerPool::serve() {
  std::size_t seen = 0;
  for (;;) {
    Handout* h = nullptr;
    {
      std::unique_lock<std::mutex> lock(m_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      h = handout_;
    }
    h->work();
    {
      const std::lock_guard<std::mutex> lock(m_);
      if (--busy_ == 0) done_.notify_one();
    }
  }
}

void WorkerPool::run(std::size_t n, const std::function<void(std::size_t)>& job) {
  if (workers_.empty() || n <= 1) {
    for (std::size_t i = 0; i < n; ++i) job(i);
    return;
  }
  Handout h(n, job);
  {
    const std::lock_guard<std::mutex> lock(m_);
    handout_ = &h;
    busy_ = static_cast<int>(workers_.size());
    ++generation_;
  }
  wake_.notify_all();
  h.work();
  {
    std::unique_lock<std::mutex> lock(m_);
    done_.wait(lock, [&] { return busy_ == 0; });
    handout_ = nullptr;
  }
  h.rethrow();
}

}  // namespace terracal

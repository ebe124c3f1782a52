// run_concurrently and WorkerPool (core/concurrent_jobs.hpp): every job once, never more than `width` at
// once, width 1 as a plain loop on the calling thread, and a failure reported as the plain loop reports it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/concurrent_jobs.hpp"

using namespace terracal;

TEST_CASE("run_concurrently runs every job once with at most width at a time", "[core][concurrent]") {
  for (const int width : {2, 3, 8}) {
    std::vector<std::atomic<int>> calls(20);
    std::atomic<int> running{0}, most{0};
    run_concurrently(calls.size(), width, [&](std::size_t i) {
      const int now = ++running;
      for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);) {
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      ++calls[i];
      --running;
    });
    INFO("width " << width);
    for (const auto& c : calls) CHECK(c.load() == 1);
    CHECK(most.load() <= width);
    CHECK(most.load() >= 2);  // they did overlap
  }
}

TEST_CASE("run_concurrently with width 1 is the plain loop on the calling thread", "[core][concurrent]") {
  std::vector<std::size_t> order;
  const auto caller = std::this_thread::get_id();
  bool same_thread = true;
  run_concurrently(5, 1, [&](std::size_t i) {
    order.push_back(i);
    same_thread = same_thread && std::this_thread::get_id() == caller;
  });
  CHECK(order == std::vector<std::size_t>{0, 1, 2, 3, 4});
  CHECK(same_thread);
  // A failure stops the loop there.
  order.clear();
  CHECK_THROWS_WITH(run_concurrently(5, 1,
                                     [&](std::size_t i) {
                                       order.push_back(i);
                                       if (i == 2) throw std::runtime_error("job 2");
                                     }),
                    "job 2");
  CHECK(order == std::vector<std::size_t>{0, 1, 2});
}

TEST_CASE("run_concurrently rethrows the failure of the lowest index and starts no job after one fails",
          "[core][concurrent]") {
  std::atomic<int> started{0};
  // Jobs 3 and 1 fail; job 3 fails first (job 1 waits), yet job 1's failure is the one reported.
  CHECK_THROWS_WITH(run_concurrently(40, 4,
                                     [&](std::size_t i) {
                                       ++started;
                                       if (i == 1) {
                                         std::this_thread::sleep_for(std::chrono::milliseconds(30));
                                         throw std::runtime_error("job 1");
                                       }
                                       if (i == 3) throw std::runtime_error("job 3");
                                       std::this_thread::sleep_for(std::chrono::milliseconds(5));
                                     }),
                    "job 1");
  CHECK(started.load() < 40);  // the hand-out stopped
}

TEST_CASE("WorkerPool runs every job once per call, at most width at a time, on threads that stay",
          "[core][concurrent]") {
  WorkerPool pool(3);
  CHECK(pool.width() == 3);
  std::vector<std::thread::id> ids;  // every thread that ran a job, over all the calls
  int overlap = 0;                   // the most jobs at once in any call
  for (int call = 0; call < 50; ++call) {
    const std::size_t n = 1 + call % 9;  // fewer jobs than threads too
    std::vector<std::atomic<int>> calls(n);
    std::atomic<int> running{0}, most{0};
    std::mutex m;
    pool.run(n, [&](std::size_t i) {
      const int now = ++running;
      for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);) {
      }
      if (call % 10 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
      {
        const std::lock_guard<std::mutex> lock(m);
        if (std::find(ids.begin(), ids.end(), std::this_thread::get_id()) == ids.end())
          ids.push_back(std::this_thread::get_id());
      }
      ++calls[i];
      --running;
    });
    INFO("call " << call << ", " << n << " jobs");
    for (const auto& c : calls) CHECK(c.load() == 1);
    CHECK(most.load() <= 3);
    overlap = std::max(overlap, most.load());
  }
  CHECK(overlap >= 2);  // they did run at once (the calls whose jobs sleep)
  // The same threads serve every call (the caller and two workers): none is started per call.
  CHECK(ids.size() <= 3);
}

TEST_CASE("WorkerPool rethrows the failure of the lowest index and serves the next call", "[core][concurrent]") {
  WorkerPool pool(4);
  CHECK_THROWS_WITH(pool.run(40,
                             [&](std::size_t i) {
                               if (i == 1) {
                                 std::this_thread::sleep_for(std::chrono::milliseconds(30));
                                 throw std::runtime_error("job 1");
                               }
                               if (i == 3) throw std::runtime_error("job 3");
                               std::this_thread::sleep_for(std::chrono::milliseconds(5));
                             }),
                    "job 1");
  std::vector<std::atomic<int>> calls(12);
  pool.run(calls.size(), [&](std::size_t i) { ++calls[i]; });
  for (const auto& c : calls) CHECK(c.load() == 1);
  // Width 1: the plain loop on the calling thread.
  WorkerPool one(1);
  std::vector<std::size_t> order;
  one.run(4, [&](std::size_t i) { order.push_back(i); });
  CHECK(order == std::vector<std::size_t>{0, 1, 2, 3});
}

// run_concurrently (core/concurrent_jobs.hpp): every job once, never more than `width` at once,
// width 1 as a plain loop on the calling thread, and a failure reported as the plain loop reports it.
#include <catch2/catch.hpp>

#include <atomic>
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

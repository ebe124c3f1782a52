#include "bayes/ceres_solve.hpp"

#include <mutex>

#include <glog/logging.h>

namespace terracal::bayes {

void solve_quietly(const ceres::Solver::Options& options, ceres::Problem* problem, ceres::Solver::Summary* summary) {
  static std::once_flag once;
  std::call_once(once, [] {
    // Initialised here unless the program did so itself (glog warns once about logging before it).
    if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging("terracal");
    FLAGS_minloglevel = google::GLOG_ERROR;
  });
  ceres::Solve(options, problem, summary);
}

}  // namespace terracal::bayes

#pragma once
// ceres::Solve without glog's warnings on stderr. A trial step whose forward run fails (a vehicle the
// step makes invalid, a diverged run) is a normal event that Ceres handles as an infinite cost, but
// it logs "Step failed to evaluate" for each: noise in a user's run that says nothing to act on.
// Errors still print. Shared by every least-squares stage.
#include <ceres/ceres.h>

namespace terracal::bayes {

void solve_quietly(const ceres::Solver::Options& options, ceres::Problem* problem, ceres::Solver::Summary* summary);

}  // namespace terracal::bayes

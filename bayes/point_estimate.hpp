#pragma once
// The first two stages of a calibration: a bounded global search (NLopt) for the basin of the
// optimum, then a least-squares polish (Ceres, with bounds) that also gives the covariance of the
// free parameters (DENSE_SVD, scaled by the residual variance). The MCMC stage starts from here.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bayes/calibration_problem.hpp"

namespace terracal::bayes {

struct PointEstimateOptions {
  std::uint64_t seed = 1;
  int global_evaluations = 20000;  // budget of the global search
  int polish_rounds = 2;           // Ceres solves, re-estimating the noise scales in between
};

struct PointEstimate {
  ParamVector map{};                 // the maximum a posteriori point (all six parameters)
  Eigen::VectorXd x;                 // its free parameters
  Eigen::MatrixXd covariance;        // of the free parameters (Laplace approximation)
  bool covariance_ok = false;        // false: some direction is not constrained by the data (see below)
  int unconstrained_directions = 0;  // directions given a floor variance (the data leave them open)
  Eigen::VectorXd noise_var;         // s_t^2 per test type at the optimum
  double weighted_rss = 0;           // sum over types of sum ((y - f)/w)^2
  int global_evaluations = 0;
  std::string ceres_report;  // Ceres' brief report of the last solve
  // Simulation-backed problems (model_point_estimate.hpp): each least-squares start's final
  // objective (the posterior with the noise profiled out, negated), and the index of the one kept.
  std::vector<double> start_objectives;
  int start = 0;
};

// Throws RunError if no feasible point is found.
PointEstimate estimate_point(const CalibrationProblem& problem, const PointEstimateOptions& options);

}  // namespace terracal::bayes

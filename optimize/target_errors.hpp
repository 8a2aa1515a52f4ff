#pragma once
// How far an equilibrium is from a target (paper section VIII's figures): the error on the tracking
// curves (what the optimizer minimizes, eq. 5) and on the whole surface (what a user sees).

#include <Eigen/Core>

#include "mesh/tet_mesh.hpp"
#include "optimize/routing_problem.hpp"

namespace fibermold {

struct TargetErrors {
  double rmse = 0, max = 0;                 ///< m, at the tracking curves' samples
  double surface_rmse = 0, surface_max = 0; ///< m, at the surface's vertices
  /// rad, the turn's error at the samples whose orientation is tracked (DistanceObjective::orientation_errors)
  double orientation_rms = 0, orientation_max = 0;
  bool orientation_tracked = false; ///< whether any sample's orientation is tracked
};

/// The errors of equilibrium x of target t of `problem`, whose body is `mesh`.
TargetErrors target_errors(RoutingProblem& problem, const TetMesh& mesh, int t, const Eigen::VectorXd& x);

} // namespace fibermold

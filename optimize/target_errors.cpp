#include "optimize/target_errors.hpp"

#include <algorithm>
#include <cmath>

namespace fibermold {

TargetErrors target_errors(RoutingProblem& problem, const TetMesh& mesh, int t, const Eigen::VectorXd& x)
{
  TargetErrors e;
  e.rmse = problem.distance(t).rmse(x);
  e.max = problem.distance(t).max_error(x);
  e.orientation_tracked = problem.distance(t).tracks_orientation();
  if (e.orientation_tracked) {
    const DistanceObjective::OrientationErrors turn = problem.distance(t).orientation_errors(x);
    e.orientation_rms = turn.rms;
    e.orientation_max = turn.max;
  }
  const Eigen::MatrixX3d reached = problem.simulation().deformed_nodes(x);
  const Eigen::MatrixX3d wanted = problem.simulation().deformed_nodes(problem.target(t));
  double sum = 0;
  for (Eigen::Index v = 0; v < mesh.surface_to_node.size(); ++v) {
    const double d = (reached.row(mesh.surface_to_node(v)) - wanted.row(mesh.surface_to_node(v))).norm();
    sum += d * d;
    e.surface_max = std::max(e.surface_max, d);
  }
  e.surface_rmse = std::sqrt(sum / static_cast<double>(std::max<Eigen::Index>(1, mesh.surface_to_node.size())));
  return e;
}

} // namespace fibermold

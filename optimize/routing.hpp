#pragma once
// A routing: each fiber's route (the Hermite spline's control points and tangents, eq. 11) and
// each target's pressures, the design that eq. 4 optimizes (routing_problem.hpp).

#include <string>
#include <vector>

#include <Eigen/Core>

namespace fibermold {

struct Route {
  std::string name;
  std::vector<Eigen::Vector3d> points, tangents; ///< m
};

/// Routes shared by all targets, and each target's pressures.
struct Routing {
  std::vector<Route> routes;
  Eigen::MatrixXd pressures; ///< targets × fibers, Pa
};

} // namespace fibermold

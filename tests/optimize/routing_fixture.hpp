#pragma once
// A small bar with fibers, targets made by known fibers, and the routing problem over it: shared by
// the gradient check and the optimization tests.

#include <memory>

#include "../sim/sim_fixtures.hpp"
#include "optimize/routing_problem.hpp"
#include "sim/external_forces.hpp"

namespace fibermold::test {

struct RoutingFixture {
  TetMesh mesh;
  MuscleModel model;
  std::unique_ptr<SurfaceDistance> skin;
  std::unique_ptr<Simulation> sim;
  std::vector<TrackingSamples> curves;

  /// A bar [0, L] × [−a/2, a/2]², held at x = 0, gravity −z, a centreline tracking curve.
  RoutingFixture(double L, double a, double edge, int samples = 20, double weight_orientation = 0.1,
                 double tolerance = 1e-10)
      : mesh(box_mesh({0, -a / 2, -a / 2}, {L, a / 2, a / 2}, edge))
  {
    skin = std::make_unique<SurfaceDistance>(mesh.nodes, mesh.boundary_faces);
    SimulationOptions o;
    o.fixed_nodes = {nodes_in_box(mesh.nodes, {-1, -1, -1}, {1e-9, 1, 1})};
    o.newton.tolerance = tolerance;
    sim = std::make_unique<Simulation>(mesh, o);
    curves = {sample_tracking_curve({{0, 0, 0}, {L, 0, 0}}, samples, 1.0, weight_orientation)};
  }

  /// The equilibrium under the given fibers (Catmull–Rom routes) and pressures.
  Eigen::VectorXd actuated(const std::vector<std::vector<Eigen::Vector3d>>& fibers,
                           const std::vector<double>& pressures, double segments_per_length = 500)
  {
    std::vector<std::unique_ptr<Energy>> muscles;
    for (std::size_t f = 0; f < fibers.size(); ++f) {
      const HermiteSpline s(fibers[f]);
      const int count = segment_count(s, segments_per_length);
      muscles.push_back(
          std::make_unique<MuscleEnergy>(sim->basis(), model, s, segment_parameters(s, count), pressures[f]));
    }
    sim->set_variable_energies(std::move(muscles));
    Eigen::VectorXd x = sim->rest();
    NullProgress progress;
    const NewtonSummary s = sim->solve(x, progress);
    if (!s.converged) throw std::runtime_error("fixture: no equilibrium: " + s.brief());
    return x;
  }

  static Route route(std::string name, const std::vector<Eigen::Vector3d>& points)
  {
    const HermiteSpline s(points);
    return {std::move(name), s.points(), s.tangents()};
  }
};

} // namespace fibermold::test

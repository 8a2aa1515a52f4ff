// Twisting bar, forward (paper section VIII-C): a helical fiber in a 129 mm bar twists its free
// end; the sense of the twist follows the helix's handedness.
#include <cmath>

#include <gtest/gtest.h>

#include "sim/external_forces.hpp"
#include "sim/muscle_energy.hpp"
#include "sim/simulation.hpp"
#include "sim_fixtures.hpp"

namespace fibermold {
namespace {

constexpr double kL = 0.129, kA = 0.02;

/// Rotation (rad) about +x of the free end face: mean angle between rest and deformed positions
/// of points around its centre.
double end_twist(const Simulation& sim, const Eigen::VectorXd& x)
{
  const Eigen::Vector3d centre = sim.basis().at({kL, 0, 0}, 0).position(x);
  double sum = 0;
  int n = 0;
  for (double a = 0; a < 2 * M_PI - 1e-9; a += M_PI / 4) {
    const Eigen::Vector3d X(kL, 0.006 * std::cos(a), 0.006 * std::sin(a));
    const Eigen::Vector3d r = sim.basis().at(X, 0).position(x) - centre;
    sum += std::remainder(std::atan2(r.z(), r.y()) - a, 2 * M_PI);
    ++n;
  }
  return sum / n;
}

double twist_with_helix(const TetMesh& mesh, double handedness, double pressure)
{
  SimulationOptions o;
  o.gravity = {9.81, 0, 0};
  o.fixed_nodes = {nodes_in_box(mesh.nodes, {-1, -1, -1}, {1e-9, 1, 1})};
  Simulation sim(mesh, o);
  // One and a half turns of radius 5 mm, from the centre of the clamped face to the centre of the free one.
  const std::vector<Eigen::Vector3d> points = test::helix_points(kL, 0.005, 1.5, handedness);
  static const MuscleModel model;
  const HermiteSpline helix(points);
  sim.add_energy(std::make_unique<MuscleEnergy>(sim.basis(), model, helix, segment_parameters(helix, 150), pressure));
  Eigen::VectorXd x = sim.rest();
  NullProgress progress;
  const NewtonSummary s = sim.solve(x, progress);
  EXPECT_TRUE(s.converged) << s.brief();
  return end_twist(sim, x);
}

TEST(TwistingBar, HelicalFiberTwistsTheFreeEndByItsHandedness)
{
  const TetMesh mesh = test::box_mesh({0, -kA / 2, -kA / 2}, {kL, kA / 2, kA / 2}, 0.0065);
  const double right = twist_with_helix(mesh, +1, 300e3), left = twist_with_helix(mesh, -1, 300e3);
  std::printf("twisting bar, 300 kPa: free end twists %.2f° (right-handed helix), %.2f° (left-handed)\n",
              right * 180 / M_PI, left * 180 / M_PI);
  EXPECT_LT(right, 0); // a contracting right-handed helix turns the free end clockwise about +x
  EXPECT_GT(left, 0);
  EXPECT_NEAR(right, -left, 0.1 * std::abs(right));
  EXPECT_GT(std::abs(right) * 180 / M_PI, 5);  // visibly twisted...
  EXPECT_LT(std::abs(right) * 180 / M_PI, 90); // ...and not absurdly
}

} // namespace
} // namespace fibermold

// The other starts of `[optimize] starts` (perturbed_start.hpp) on a 16 mm bar: moved by the spread
// asked where the bar has room, the same for the same start number, other for another, always a
// design the optimizer accepts, the ends and pressures kept; and halved where the room is short.
#include <cmath>

#include <gtest/gtest.h>

#include "optimize/perturbed_start.hpp"
#include "optimize/routing_problem.hpp"
#include "routing_fixture.hpp"

namespace fibermold {
namespace {

/// The RMS move of the interior control points of r's first route from s's.
double rms_move(const Routing& r, const Routing& s)
{
  double sum = 0;
  int n = 0;
  for (std::size_t i = 1; i + 1 < r.routes[0].points.size(); ++i, n += 3)
    sum += (r.routes[0].points[i] - s.routes[0].points[i]).squaredNorm();
  return std::sqrt(sum / n);
}

TEST(PerturbedStart, MovesTheInteriorPointsBySpreadAndStaysADesignTheOptimizerAccepts)
{
  constexpr double L = 0.08, a = 0.016;
  test::RoutingFixture fx(L, a, 0.008, 20, 0.1, 1e-9);
  const std::vector<Eigen::VectorXd> targets{fx.actuated({{{0, 0, 0.004}, {L, 0, 0.004}}}, {300e3})};
  Routing start;
  start.routes = {test::RoutingFixture::route("m1", {{0, 0, 0}, {0.02, 0, 0}, {0.04, 0, 0}, {0.06, 0, 0}, {L, 0, 0}})};
  start.pressures = Eigen::MatrixXd::Constant(1, 1, 200e3);
  RoutingProblem problem(*fx.sim, fx.model, *fx.skin, targets, fx.curves, start, {});

  const Routing one = perturbed_start(problem, start, 1, 0.5e-3);
  const Routing again = perturbed_start(problem, start, 1, 0.5e-3);
  const Routing two = perturbed_start(problem, start, 2, 0.5e-3);
  for (std::size_t i = 0; i < one.routes[0].points.size(); ++i) {
    EXPECT_EQ(one.routes[0].points[i], again.routes[0].points[i]);
    EXPECT_EQ(one.routes[0].tangents[i], again.routes[0].tangents[i]);
  }
  EXPECT_EQ(one.routes[0].points.front(), start.routes[0].points.front());
  EXPECT_EQ(one.routes[0].points.back(), start.routes[0].points.back());
  EXPECT_EQ(one.pressures, start.pressures);
  // 9 normal deviates: their RMS within a factor of 2 of 1 (about 97 % of draws; these are fixed).
  EXPECT_GT(rms_move(one, start), 0.25e-3);
  EXPECT_LT(rms_move(one, start), 1e-3);
  EXPECT_GT(rms_move(two, one), 0.1e-3) << "another start number, another start";
  for (const Routing* r : {&one, &two}) {
    problem.set_base(*r);
    EXPECT_TRUE(std::isfinite(problem.regularizer_value(problem.variables(*r))));
  }
  problem.set_base(start);

  // Asked to move by 20 mm in a 16 mm bar: halved until the route stays inside, clear of the skin.
  const Routing far = perturbed_start(problem, start, 1, 20e-3);
  const double moved = rms_move(far, start);
  EXPECT_GT(moved, 0);
  EXPECT_LT(moved, 5e-3);
  problem.set_base(far);
  EXPECT_TRUE(std::isfinite(problem.regularizer_value(problem.variables(far))));
  std::printf("perturbed starts: RMS move %.3f mm (spread 0.5 mm), %.3f mm (spread 20 mm, halved)\n",
              rms_move(one, start) * 1e3, moved * 1e3);
}

} // namespace
} // namespace fibermold

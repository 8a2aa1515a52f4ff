#include "optimize/optimization_ending.hpp"

#include <cmath>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/units.hpp"
#include "optimize/bend_radius.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

constexpr double kDeg = M_PI / 180;

/// One target, one fiber at `pressure` (Pa) of max 425 kPa, tracking-curve RMSE `start` → `end` (m).
OptimizationEnding ending(double pressure, double start, double end, const std::vector<AngleReach>& turns,
                          bool converged = true)
{
  RoutingResult r;
  r.routing.pressures = Eigen::MatrixXd::Constant(1, 1, pressure);
  r.converged = converged;
  r.termination = converged ? Termination::gradient_tolerance : Termination::iteration_limit;
  r.message = "test";
  RoutingSettings s;
  s.max_pressure = 425e3;
  TargetErrors before, after;
  before.rmse = start;
  after.rmse = end;
  return optimization_ending(r, ActuatorMask::Constant(1, 1, true), s, {before}, {after}, {turns}, {"curl"},
                             {"flexor"});
}

// A region that turned 71 % of its angle is not far from reached, but short of its turn: said with
// the muscles' pressures and, with pressure to spare, what holds it back (a new user's starfish
// curled 28.5° of a 40° grasp at 280 of 425 kPa, and nothing said so).
TEST(OptimizationEnding, ATurnShortOfItsAngleIsSaidWithThePressuresAndWhatHoldsItBack)
{
  const OptimizationEnding spare = ending(280e3, 4.9e-3, 1e-3, {{"pose[1]", 40 * kDeg, 28.5 * kDeg}});
  ASSERT_EQ(spare.warnings.size(), 1u);
  EXPECT_THAT(spare.warnings[0], HasSubstr("target curl is short of its turn: pose[1] turned 28.5° of the 40.0° "
                                           "asked (71 %), its muscles at 280 kPa of [muscle] max_pressure = 425 kPa"));
  EXPECT_THAT(spare.warnings[0], HasSubstr("raise the tracking curves' weight_orientation"));
  // At max_pressure the muscle is what holds it back.
  const OptimizationEnding limited = ending(425e3, 4.9e-3, 1e-3, {{"pose[1]", 40 * kDeg, 28.5 * kDeg}});
  ASSERT_EQ(limited.warnings.size(), 2u); // the fiber at its limit, and the turn
  EXPECT_THAT(limited.warnings[1], HasSubstr("short of its turn"));
  EXPECT_THAT(limited.warnings[1], HasSubstr("a muscle is at max_pressure"));
  // 90 % and more is reached; under 2/3 is far from reached, said once as such.
  EXPECT_TRUE(ending(280e3, 4.9e-3, 1e-3, {{"pose[1]", 40 * kDeg, 36 * kDeg}}).warnings.empty());
  const OptimizationEnding far = ending(280e3, 4.9e-3, 1e-3, {{"pose[1]", 40 * kDeg, 20 * kDeg}});
  ASSERT_EQ(far.warnings.size(), 1u);
  EXPECT_THAT(far.warnings[0], HasSubstr("far from reached"));
}

TEST(OptimizationEnding, APoseTargetIsJudgedByItsTurnNotItsTrackingCurves)
{
  // The curves kept most of their error, but the tip turned 54° of 60°: not far from reached.
  EXPECT_TRUE(ending(230e3, 4.9e-3, 4.3e-3, {{"pose[1]", 60 * kDeg, 54 * kDeg}}).warnings.empty());
  // 38° of 60° is: the warning names the region, both angles and the share.
  const OptimizationEnding far = ending(230e3, 4.9e-3, 1e-3, {{"pose[1]", 60 * kDeg, 38 * kDeg}});
  ASSERT_EQ(far.warnings.size(), 1u);
  EXPECT_THAT(far.warnings[0],
              HasSubstr("target curl is far from reached: pose[1] turned 38.0° of the 60.0° asked (63 %)"));
  // A turn the other way says what to check.
  const OptimizationEnding back = ending(230e3, 4.9e-3, 1e-3, {{"pose[1]", 45 * kDeg, -28.7 * kDeg}});
  ASSERT_EQ(back.warnings.size(), 1u);
  EXPECT_THAT(
      back.warnings[0],
      HasSubstr("pose[1] turned -28.7° of the 45.0° asked (-64 %: the other way; check the sign of the pose's axis"));
  // Two regions short of their turns are both named.
  const OptimizationEnding two =
      ending(230e3, 4.9e-3, 1e-3, {{"pose[1]", 60 * kDeg, 30 * kDeg}, {"pose[2]", -40 * kDeg, -10 * kDeg}});
  ASSERT_EQ(two.warnings.size(), 1u);
  EXPECT_THAT(
      two.warnings[0],
      HasSubstr("pose[1] turned 30.0° of the 60.0° asked (50 %), pose[2] turned -10.0° of the -40.0° asked (25 %)"));
}

// Only a run cut short by the limit is told to raise it: a stalled one would stall again.
TEST(OptimizationEnding, OnlyARunAtTheIterationLimitIsToldToRaiseIt)
{
  RoutingResult r;
  r.routing.pressures = Eigen::MatrixXd::Constant(1, 1, 200e3);
  r.converged = false;
  r.termination = Termination::stalled;
  r.message = "f fell by 1e-9 of itself over 10 iterations";
  RoutingSettings s;
  s.max_pressure = 425e3;
  TargetErrors before, after;
  before.rmse = 3e-3;
  after.rmse = 0.5e-3;
  const OptimizationEnding stalled =
      optimization_ending(r, ActuatorMask::Constant(1, 1, true), s, {before}, {after}, {{}}, {"curl"}, {"flexor"});
  ASSERT_EQ(stalled.warnings.size(), 1u);
  EXPECT_THAT(stalled.warnings[0], HasSubstr("stopped before converging (stalled: f fell"));
  EXPECT_THAT(stalled.warnings[0], Not(HasSubstr("max_iterations")));
}

TEST(OptimizationEnding, ATargetWithoutATurnIsJudgedByItsTrackingCurvesAndALimitIsNamed)
{
  EXPECT_TRUE(ending(230e3, 3e-3, 0.9e-3, {}).warnings.empty()); // 70 % of the way
  const OptimizationEnding far = ending(424e3, 3e-3, 1.5e-3, {}, false);
  ASSERT_EQ(far.warnings.size(), 3u);
  EXPECT_THAT(far.warnings[0], HasSubstr("stopped before converging (iteration limit: test)"));
  EXPECT_THAT(far.warnings[0], HasSubstr("raise [optimize] max_iterations"));
  EXPECT_THAT(far.warnings[1], HasSubstr("fiber flexor ends at 424.0 kPa, at its limit"));
  EXPECT_THAT(far.warnings[2],
              HasSubstr("far from reached: 50 % of the way (tracking-curve RMSE 3.00 → 1.50 mm); its muscles are at "
                        "max_pressure"));
  ASSERT_EQ(far.limits.size(), 1u);
  EXPECT_TRUE(far.limits[0].at_max);
}

TEST(OptimizationEnding, ATargetWithEveryMuscleOffIsSaidToBeTheBodyUnactuatedWithWhatToCheck)
{
  // A new user's level finger sagged 54 mm under its weight, past the 45° asked: the optimizer
  // turned the muscle off, and the warning pointed at the route, not at how the body is held.
  const OptimizationEnding off = ending(0.9, 52e-3, 4.1e-3, {{"pose[1]", 45 * kDeg, 46.4 * kDeg}});
  ASSERT_EQ(off.warnings.size(), 1u);
  EXPECT_THAT(off.warnings[0], HasSubstr("target curl: every muscle of it ends at 0 kPa"));
  EXPECT_THAT(off.warnings[0], HasSubstr("(at most 8.5 kPa, the pressure barrier's margin)"));
  EXPECT_THAT(off.warnings[0], HasSubstr("the body unactuated, which its weight and how it is held alone bring to a "
                                         "tracking-curve RMSE of 4.10 mm"));
  EXPECT_THAT(off.warnings[0], HasSubstr("check [material] gravity and the [[fixed]] regions"));
  EXPECT_THAT(off.warnings[0], Not(HasSubstr("turned it off")));
  ASSERT_EQ(off.limits.size(), 1u);
  EXPECT_FALSE(off.limits[0].at_max);

  // With another muscle on, the one turned off is named on its own.
  RoutingResult r;
  r.routing.pressures = (Eigen::MatrixXd(1, 2) << 0.0, 200e3).finished();
  r.converged = true;
  RoutingSettings s;
  s.max_pressure = 425e3;
  TargetErrors before, after;
  before.rmse = 52e-3;
  after.rmse = 4.1e-3;
  const OptimizationEnding one = optimization_ending(r, ActuatorMask::Constant(1, 2, true), s, {before}, {after}, {{}},
                                                     {"curl"}, {"flexor", "extensor"});
  ASSERT_EQ(one.warnings.size(), 1u);
  EXPECT_THAT(one.warnings[0], HasSubstr("fiber flexor ends at 0.0 kPa: the optimizer turned it off"));
  // A muscle meant for another target: the warning says how to say so, and then it is not said.
  EXPECT_THAT(one.warnings[0], HasSubstr("if it is not meant to, list the fibers that are in the target's actuators"));
  const ActuatorMask extensor_only = (ActuatorMask(1, 2) << false, true).finished();
  EXPECT_TRUE(optimization_ending(r, extensor_only, s, {before}, {after}, {{}}, {"curl"}, {"flexor", "extensor"})
                  .warnings.empty());
}

TEST(OptimizationEnding, AFirstGuessWhoseMusclesDoBestOffIsSaidToWorkAgainstTheTarget)
{
  // A new user's finger held level (session 41): its weight alone turned the tip 36.4° of the 45°
  // asked and dropped it past the target, so the straight muscle did best at 0.0016 kPa; the
  // optimizer then moved the muscle to lift the finger, and nothing said why.
  RoutingSettings s;
  s.max_pressure = 425e3;
  const ActuatorMask both = ActuatorMask::Constant(2, 2, true);
  const Eigen::MatrixXd p = (Eigen::MatrixXd(2, 2) << 1.6, 8e3, 0.0, 150e3).finished(); // target 2: one muscle on
  const std::vector<std::string> w = first_guess_warnings(p, both, s, {6.77e-3, 2e-3}, {"curl", "lift"});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_THAT(w[0], HasSubstr("target curl: the first guess's muscles do best at 0 kPa (at most 8.5 kPa)"));
  EXPECT_THAT(w[0], HasSubstr("(tracking-curve RMSE 6.77 mm at those pressures)"));
  EXPECT_THAT(w[0], HasSubstr("check [material] gravity and the [[fixed]] regions"));
  // A muscle a target does not actuate does not count: curl's own muscle is off (the other, on, is
  // not curl's), and lift's two are off.
  ActuatorMask curl_first = both;
  curl_first(0, 1) = false;
  const Eigen::MatrixXd q = (Eigen::MatrixXd(2, 2) << 0.0, 100e3, 0.0, 0.0).finished();
  const std::vector<std::string> off = first_guess_warnings(q, curl_first, s, {1e-3, 1e-3}, {"curl", "lift"});
  ASSERT_EQ(off.size(), 2u);
  EXPECT_THAT(off[0], HasSubstr("target curl"));
  EXPECT_THAT(off[1], HasSubstr("target lift"));
}

TEST(OptimizationEnding, ARouteAtItsSmallestBendRadiusIsNamedWithWhereAndWhatToTry)
{
  // A Hermite quarter turn between points 10 mm off a corner: its tightest bend, 8.6 mm where the
  // arc strays from the circle, is at a limit 1 % below it and not at one 5 % below.
  RoutingResult r;
  r.routing.pressures = Eigen::MatrixXd::Constant(1, 1, 200e3);
  r.converged = true;
  r.termination = Termination::decrease_tolerance;
  const double R = 10e-3, k = M_PI / 2 * R;
  r.routing.routes.push_back({"flexor",
                              {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(R, R, 0)},
                              {Eigen::Vector3d(k, 0, 0), Eigen::Vector3d(0, k, 0)}});
  const SmallestBend tightest = smallest_bend(HermiteSpline(r.routing.routes[0].points, r.routing.routes[0].tangents));
  ASSERT_NEAR(tightest.radius, 8.63e-3, 0.01e-3);
  TargetErrors before, after;
  before.rmse = 3e-3;
  after.rmse = 1.5e-3; // far from reached
  RoutingSettings s;
  s.max_pressure = 425e3;
  const auto end_with = [&](double min_radius) {
    s.min_bend_radius = min_radius;
    return optimization_ending(r, ActuatorMask::Constant(1, 1, true), s, {before}, {after}, {{}}, {"curl"}, {"flexor"});
  };
  const OptimizationEnding at = end_with(tightest.radius / 1.01);
  ASSERT_EQ(at.bends.size(), 1u);
  EXPECT_EQ(at.bends[0].fiber, 0);
  EXPECT_DOUBLE_EQ(at.bends[0].radius, tightest.radius);
  ASSERT_EQ(at.warnings.size(), 2u);
  EXPECT_THAT(at.warnings[0], HasSubstr(fmt::format("fiber flexor bends through {:.2f} mm at {}", tightest.radius * 1e3,
                                                    format_mm(tightest.where))));
  EXPECT_THAT(at.warnings[0], HasSubstr("at its limit, [muscle] min_bend_radius"));
  EXPECT_THAT(at.warnings[0], HasSubstr("the bend radius, not the targets, decides the route"));
  EXPECT_THAT(at.warnings[1], HasSubstr("far from reached"));
  EXPECT_THAT(at.warnings[1], HasSubstr("lower [muscle] min_bend_radius only if the muscle takes a tighter bend"));
  const OptimizationEnding clear = end_with(tightest.radius / 1.05);
  EXPECT_TRUE(clear.bends.empty());
  ASSERT_EQ(clear.warnings.size(), 1u);
  EXPECT_THAT(clear.warnings[0], Not(HasSubstr("bend radius")));
}

} // namespace
} // namespace fibermold

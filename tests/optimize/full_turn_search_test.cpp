// The secant search for the pressure scale that turns a region its whole angle
// (optimize/full_turn_search.hpp), on turns θ(s) known in closed form: the solves it makes, where it
// stops, the cap at max_pressure, a negative angle, a turn that stops growing, a failed solve.
#include <cmath>
#include <optional>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/progress.hpp"
#include "optimize/full_turn_search.hpp"

namespace fibermold {
namespace {

/// θ(s) = c s^1.5: a turn that grows faster than the pressure, as a soft body's does.
struct Stiffening {
  double c;
  int solves = 0;
  double operator()(double s)
  {
    ++solves;
    return c * std::pow(s, 1.5);
  }
  /// The search for `angle` from the turns at 0.9 and 1.1 (collide's ±10 % pressures), up to `most`.
  std::optional<FullTurn> search(double angle, double most)
  {
    return full_turn_search(angle, 0.9, c * std::pow(0.9, 1.5), 1.1, c * std::pow(1.1, 1.5), most,
                            [&](double s) { return (*this)(s); });
  }
};

TEST(FullTurnSearch, FindsTheScaleOfAGrowingTurnWithinTheTolerance)
{
  // 28° at s = 1 and 40° asked: s* = (40/28)^(2/3) = 1.268.
  Stiffening turn{28};
  const auto found = turn.search(40, 10);
  ASSERT_TRUE(found);
  EXPECT_TRUE(found->reached);
  EXPECT_FALSE(found->at_most);
  EXPECT_NEAR(found->turn, 40, 0.02 * 40);
  EXPECT_NEAR(found->scale, std::pow(40.0 / 28, 2.0 / 3), 0.02);
  EXPECT_EQ(turn.solves, 1); // the first step from the ±10 % secant: 40.72°, 1.8 % over
}

TEST(FullTurnSearch, ANegativeAngleIsSearchedAlike)
{
  Stiffening turn{-28};
  const auto found = turn.search(-40, 10);
  ASSERT_TRUE(found);
  EXPECT_TRUE(found->reached);
  EXPECT_NEAR(found->turn, -40, 0.8);
}

TEST(FullTurnSearch, StopsAtTheMostAndSaysSo)
{
  // The highest pressure may rise by 1.2 at most: θ(1.2) = 36.8° of the 40° asked.
  Stiffening turn{28};
  const auto found = turn.search(40, 1.2);
  ASSERT_TRUE(found);
  EXPECT_TRUE(found->at_most);
  EXPECT_FALSE(found->reached);
  EXPECT_DOUBLE_EQ(found->scale, 1.2);
  EXPECT_NEAR(found->turn, 28 * std::pow(1.2, 1.5), 1e-12);
  EXPECT_EQ(turn.solves, 1); // short at the most: no further solve
}

TEST(FullTurnSearch, ATurnThatDoesNotGrowTowardTheAngleIsNotSearched)
{
  int solves = 0;
  const auto count = [&](double) { return ++solves, 0.0; };
  EXPECT_FALSE(full_turn_search(40, 0.9, 30, 1.1, 29, 10, count)); // falls with the pressure
  EXPECT_FALSE(full_turn_search(-40, 0.9, 3, 1.1, 4, 10, count));  // grows the other way
  EXPECT_EQ(solves, 0);
}

TEST(FullTurnSearch, AFailedSolveEndsTheSearchWithTheNearestSoFarAndInterruptedPassesThrough)
{
  // θ(s) = 20 s, but no equilibrium above s = 1.6: the first step (s = 2) fails, nothing solved.
  const auto linear = [](double s) {
    if (s > 1.6) throw std::runtime_error("no equilibrium");
    return 20 * s;
  };
  EXPECT_FALSE(full_turn_search(40, 0.9, 18, 1.1, 22, 10, linear));
  // A turn that overshoots, then fails: the overshoot is the nearest.
  int solves = 0;
  const auto bends_then_fails = [&](double s) {
    if (++solves > 1) throw std::runtime_error("no equilibrium");
    return 25 * s * s;
  };
  const auto found = full_turn_search(40, 0.9, 25 * 0.81, 1.1, 25 * 1.21, 10, bends_then_fails);
  ASSERT_TRUE(found);
  EXPECT_FALSE(found->reached);
  EXPECT_EQ(solves, 2);
  EXPECT_THROW(full_turn_search(40, 0.9, 18, 1.1, 22, 10, [](double) -> double { throw Interrupted(); }), Interrupted);
}

} // namespace
} // namespace fibermold

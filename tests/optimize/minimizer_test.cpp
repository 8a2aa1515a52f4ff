// The stall rules (minimizer.hpp) on the last eleven iterations of two runs of session 37
// (history.csv: the objective and the model's predicted decrease after each iteration). Over both
// windows f fell by under 1e-3 of its value, so the relative-tolerance rule alone calls both
// stalls. Levenberg-Marquardt's rule asks too that the model kept predicting more than that:
// the walking robot's did at all ten iterations (against a wall: its steps had shrunk to 1e-5
// units), the twisting bar's at the last alone, and that run went on to converge 53 iterations
// later.
#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "optimize/minimizer.hpp"

namespace fibermold {
namespace {

struct Window {
  std::vector<double> values, predicted;
};

// examples/walking-robot, iterations 242-252 (f) and 243-252 (the predicted decrease).
const Window kWalkingRobot{
    {2.04392938, 2.04392915, 2.04362187, 2.04321895, 2.04321876, 2.0429494, 2.0429493, 2.04287294, 2.04277996,
     2.04277984, 2.0427798},
    {0.0168965, 0.0236018, 0.00921476, 0.0516829, 0.00925905, 0.0532361, 0.0438604, 0.0324561, 0.0100462, 0.0343507}};

// examples/twisting-bar, iterations 429-439 and 430-439.
const Window kTwistingBar{{0.64188567, 0.64187415, 0.641857897, 0.641852713, 0.641830885, 0.641828542, 0.64180763,
                           0.641807615, 0.641805915, 0.641788571, 0.641755037},
                          {0.000484594, 0.000104312, 0.000486612, 0.000100532, 0.000485005, 0.000466622, 9.79715e-05,
                           0.000479292, 0.000294671, 0.000810256}};

TEST(StallRules, AModelThatKeptPredictingWhatItDidNotDeliverIsAStall)
{
  const MinimizerOptions o; // relative_tolerance 1e-3 over 10 iterations
  ASSERT_TRUE(stall_message(kWalkingRobot.values, kWalkingRobot.values.back(), o));
  const auto message = model_stall_message(kWalkingRobot.values, kWalkingRobot.predicted, o);
  ASSERT_TRUE(message);
  EXPECT_EQ(*message, "f fell by 0.000563 of its value over the last 10 iterations");
}

TEST(StallRules, AModelThatPredictedLittleLeftAtOneIterationOfTheWindowIsNotAStall)
{
  const MinimizerOptions o;
  EXPECT_TRUE(stall_message(kTwistingBar.values, kTwistingBar.values.back(), o)); // f alone: a stall
  EXPECT_GT(kTwistingBar.predicted.back(),
            o.relative_tolerance * kTwistingBar.values.back()); // and the last prediction
  EXPECT_FALSE(model_stall_message(kTwistingBar.values, kTwistingBar.predicted, o));

  // The same window with every prediction raised above the tolerance is a stall again, and one
  // prediction under it anywhere in the window (here the first) is not.
  Window raised = kTwistingBar;
  for (double& p : raised.predicted) p = std::max(p, 1e-3);
  EXPECT_TRUE(model_stall_message(raised.values, raised.predicted, o));
  raised.predicted.front() = 1e-4;
  EXPECT_FALSE(model_stall_message(raised.values, raised.predicted, o));
}

TEST(StallRules, OnlyTheLastWindowsPredictionsCount)
{
  // The walking robot's window after an iteration whose model predicted little: that iteration is
  // outside the window, so the run stalls all the same; inside it, it would not.
  const MinimizerOptions o;
  Window longer = kWalkingRobot;
  longer.values.insert(longer.values.begin(), 2.04393);
  longer.predicted.insert(longer.predicted.begin(), 1e-6);
  EXPECT_TRUE(model_stall_message(longer.values, longer.predicted, o));
  longer.predicted[5] = 1e-6;
  EXPECT_FALSE(model_stall_message(longer.values, longer.predicted, o));
  // Fewer than a window of iterations: no stall.
  const Window shorter{std::vector<double>(kWalkingRobot.values.begin() + 1, kWalkingRobot.values.end()),
                       std::vector<double>(kWalkingRobot.predicted.begin() + 1, kWalkingRobot.predicted.end())};
  EXPECT_FALSE(model_stall_message(shorter.values, shorter.predicted, o));
}

} // namespace
} // namespace fibermold

// Which of the optimized routing and the first guess at its best pressures the optimize stage keeps.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "optimize/first_guess_comparison.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

RoutingTerms terms(double distance, double skin, double bend = 0, double curvature = 0)
{
  RoutingTerms t;
  t.distance = distance;
  t.skin = skin;
  t.bend = bend;
  t.curvature = curvature;
  t.total = distance + skin + bend + curvature;
  return t;
}

TEST(FirstGuessComparison, AHigherObjectiveKeepsTheFirstGuess)
{
  const FirstGuessComparison c = compare_with_first_guess(terms(1.0, 0.5), terms(1.2, 0.4));
  EXPECT_TRUE(c.keep_first_guess);
  EXPECT_THAT(c.warning, HasSubstr("an objective of 1.6, above the first guess's at its best pressures (1.5)"));
}

TEST(FirstGuessComparison, AWorseMatchBoughtWithTheBarriersKeepsTheFirstGuessAndNamesWhatFell)
{
  // The new user's hanging finger (session 41): the straight muscle 3 mm from the skin paid 15.6 in
  // skin barrier; the optimizer moved it inward to 0.35 and its distance rose from 4.71 to 5.72.
  const FirstGuessComparison c =
      compare_with_first_guess(terms(4.706, 15.62, 0.01, 0.0), terms(5.723, 0.3457, 0.0028, 0.0037));
  EXPECT_TRUE(c.keep_first_guess);
  EXPECT_THAT(c.warning, HasSubstr("match the targets less well than the first guess at its best pressures "
                                   "(distance 5.723 against 4.706)"));
  EXPECT_THAT(c.warning, HasSubstr("through the skin barrier 15.62 -> 0.3457 ([optimize] weight_skin_barrier), "
                                   "the bend barrier 0.01 -> 0.0028 ([optimize] weight_bend_barrier), not"));
  EXPECT_THAT(c.warning, Not(HasSubstr("curvature"))); // it rose
}

TEST(FirstGuessComparison, ABetterMatchAtALowerObjectiveKeepsTheOptimizedRoutes)
{
  const FirstGuessComparison c = compare_with_first_guess(terms(7.10, 0.5), terms(2.80, 0.6));
  EXPECT_FALSE(c.keep_first_guess);
  EXPECT_TRUE(c.warning.empty());
}

TEST(FirstGuessComparison, TheSameMatchWithinRoundOffKeepsTheOptimizedRoutes)
{
  // An optimizer that stayed at the first guess's routes scores their distance to the last digits.
  EXPECT_FALSE(compare_with_first_guess(terms(2.0, 0.5), terms(2.0 * (1 + 1e-12), 0.3)).keep_first_guess);
  EXPECT_TRUE(compare_with_first_guess(terms(2.0, 0.5), terms(2.0 * (1 + 1e-6), 0.3)).keep_first_guess);
}

} // namespace
} // namespace fibermold

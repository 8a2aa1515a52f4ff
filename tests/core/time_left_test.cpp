// The time left from a progress fraction: none before 2 s and 2 % of the work, then the elapsed
// time scaled by what is left over what was done since the first report.
#include <gtest/gtest.h>

#include "core/time_left.hpp"

namespace fibermold {
namespace {

TEST(TimeLeft, ScalesTheElapsedTimeByTheWorkLeft)
{
  TimeLeft left;
  const auto t0 = TimeLeft::Clock::time_point{} + std::chrono::hours(1);
  const auto at = [&](double s) {
    return t0 + std::chrono::duration_cast<TimeLeft::Clock::duration>(std::chrono::duration<double>(s));
  };
  EXPECT_FALSE(left.seconds(0.1, at(0)));    // the first report starts the clock
  EXPECT_FALSE(left.seconds(0.5, at(1)));    // under 2 s
  EXPECT_FALSE(left.seconds(0.105, at(10))); // under 2 % of the work
  ASSERT_TRUE(left.seconds(0.5, at(4)));
  EXPECT_NEAR(*left.seconds(0.5, at(4)), 4 * 0.5 / 0.4, 1e-9); // 0.4 done in 4 s, 0.5 to go
  EXPECT_NEAR(*left.seconds(1.0, at(9)), 0.0, 1e-12);
  EXPECT_FALSE(left.seconds(-1, at(9))); // unknown
}

TEST(TimeLeft, ReadsAsAPersonWouldSayIt)
{
  EXPECT_EQ(TimeLeft::format(39.6), "40 s");
  EXPECT_EQ(TimeLeft::format(190), "3 min 10 s");
  EXPECT_EQ(TimeLeft::format(180), "3 min");
  EXPECT_EQ(TimeLeft::format(7500), "2 h 5 min");
  EXPECT_EQ(TimeLeft::format(-3), "0 s");
}

} // namespace
} // namespace fibermold

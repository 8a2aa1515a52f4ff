#include "sim/hermite_spline.hpp"

#include <gtest/gtest.h>

namespace fibermold {
namespace {

TEST(HermiteSpline, InterpolatesItsPointsAndMeasuresLength)
{
  const HermiteSpline line({{0, 0, 0}, {0.04, 0, 0}, {0.1, 0, 0}});
  EXPECT_LT((line.position(1) - Eigen::Vector3d(0.04, 0, 0)).norm(), 1e-15);
  EXPECT_LT((line.position(2) - Eigen::Vector3d(0.1, 0, 0)).norm(), 1e-15);
  EXPECT_NEAR(line.length(), 0.1, 1e-6);

  // A quarter circle through 3 points with exact tangents: length π r / 2 within the cubic's accuracy.
  const double r = 0.02;
  const HermiteSpline arc({{r, 0, 0}, {r / std::sqrt(2.0), r / std::sqrt(2.0), 0}, {0, r, 0}},
                          {Eigen::Vector3d(0, 1, 0) * r * M_PI / 4,
                           Eigen::Vector3d(-1, 1, 0).normalized() * r * M_PI / 4,
                           Eigen::Vector3d(-1, 0, 0) * r * M_PI / 4});
  EXPECT_NEAR(arc.length(), M_PI * r / 2, 1e-3 * M_PI * r / 2); // a cubic per 45° of arc
  // Between parameters: a third of the quarter circle (15° of its 45° in the first span: with the
  // cubic's uneven speed, 1e-2), pieces add up to the whole.
  EXPECT_NEAR(arc.length(0, 2) / arc.length(), 1, 1e-15);
  EXPECT_NEAR(arc.length(0, 1.0 / 3) / (M_PI * r / 12), 1, 1e-2);
  EXPECT_NEAR(arc.length(0, 0.7) + arc.length(0.7, 1.6) + arc.length(1.6, 2), arc.length(), 1e-9 * arc.length());
  EXPECT_NEAR(line.length(0.5, 1.5), 0.05, 1e-6); // 0.02 of the first span, 0.03 of the second
}

TEST(HermiteSpline, SegmentsFollowTheCurveInProportionToSpanLength)
{
  const HermiteSpline line({{0, 0, 0}, {0.02, 0, 0}, {0.1, 0, 0}});
  const FiberSegments s = split_into_segments(line, 10);
  ASSERT_EQ(s.centres.size(), 10u);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& d : s.vectors) sum += d;
  EXPECT_LT((sum - Eigen::Vector3d(0.1, 0, 0)).norm(), 1e-15);
  int first_span = 0;
  for (double t : s.t) first_span += t < 1;
  EXPECT_EQ(first_span, 2);                                   // 20 % of the length, 20 % of the segments
  EXPECT_EQ(split_into_segments(line, 1).centres.size(), 2u); // at least one per span
}

} // namespace
} // namespace fibermold

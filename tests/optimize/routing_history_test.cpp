// optimize/history.csv's rows (optimize/routing_history.hpp).
#include "optimize/routing_history.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace fibermold {
namespace {

TEST(RoutingHistory, EachRowHoldsEveryTermEachTargetsDistanceAndTheStep)
{
  RoutingHistory history({"bend", "twist"});
  RoutingTerms terms{6.5, 4, 1, 0.5, 0.25, 0.5, 0.25, {3, 1}};
  history.add(3, 0, {3, 6.5, 0.125, 0.5, 7, 0.75}, terms, 1.25, 0);
  history.add(4, -1, {4, 6, 0.0625, 1, 9, std::nan("")}, terms, 2.5, 1); // Levenberg-Marquardt: no prediction
  EXPECT_EQ(history.text(),
            "iteration,stage,objective,distance,curvature,skin_barrier,bend_barrier,pressure_barrier,clearance_barrier,"
            "distance_bend,distance_twist,gradient_norm,predicted_decrease,step,evaluations,seconds,start\n"
            "3,1,6.5,4,1,0.5,0.25,0.5,0.25,3,1,0.125,0.75,0.5,7,1.250,0\n"
            "4,0,6.5,4,1,0.5,0.25,0.5,0.25,3,1,0.0625,,1,9,2.500,1\n");
}

} // namespace
} // namespace fibermold

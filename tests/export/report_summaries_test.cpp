// What report.html and README.txt say of the optimization and of collide, from their reports
// (export/optimization_summary.hpp, export/behaviour_summary.hpp).
#include <gtest/gtest.h>

#include "export/behaviour_summary.hpp"
#include "export/optimization_summary.hpp"

namespace fibermold {
namespace {

using Json = nlohmann::ordered_json;

const Json kOptimized = Json::parse(R"({
  "optimized": true, "termination": "converged", "iterations": 42, "message": "gradient small",
  "warnings": ["target bend reached 40 % of its error", 7],
  "targets": {
    "bend": {"rmse_mm": 1.25, "reached_percent": 60.4, "start": {"rmse_mm": 3.125},
             "pressure_kPa": {"m1": 80.04, "m2": 0},
             "poses": [{"place": "pose[1]", "asked_rotation_deg": 60, "rotation_about_asked_axis_deg": 54.06}]},
    "twist": {"rmse_mm": 0.5, "reached_percent": 90, "start": {"rmse_mm": 5},
              "pressure_kPa": {"m1": 0, "m2": 120.26}}
  }})");

TEST(OptimizationSummary, TheTableGivesEachTargetsErrorsTurnsAndPressures)
{
  ASSERT_TRUE(optimized_targets(kOptimized));
  const ReportTable t = optimization_table(kOptimized);
  EXPECT_EQ(t.title, "Optimization: converged after 42 iterations (gradient small)");
  EXPECT_EQ(t.header,
            (std::vector<std::string>{"target", "RMSE at the start (mm)", "RMSE at the end (mm)",
                                      "reached: 1 − end / start RMSE", "turn reached", "m1 (kPa)", "m2 (kPa)"}));
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0],
            (std::vector<std::string>{"bend", "3.125", "1.250", "60 %", "54.1° of 60.0° (pose[1])", "80.0", "0.0"}));
  EXPECT_EQ(t.rows[1], (std::vector<std::string>{"twist", "5.000", "0.500", "90 %", "–", "0.0", "120.3"}));
}

TEST(OptimizationSummary, OnlyAReportThatOptimizedTargetsCounts)
{
  EXPECT_FALSE(optimized_targets(Json::parse(R"({"optimized": false, "targets": {"a": {}}})")));
  EXPECT_FALSE(optimized_targets(Json::parse(R"({"optimized": true, "targets": {}})")));
  EXPECT_FALSE(optimized_targets(Json::parse(R"({"optimized": true})")));
}

TEST(OptimizationSummary, WarningsAreTheReportsStringsWrappedForReadme)
{
  EXPECT_EQ(optimization_warnings(kOptimized), std::vector<std::string>{"target bend reached 40 % of its error"});
  const std::string text = optimization_warnings_text(kOptimized);
  EXPECT_NE(text.find("\n  - target bend reached 40 % of its error\n"), std::string::npos) << text;
  EXPECT_EQ(optimization_warnings_text(Json::parse(R"({"warnings": []})")), "");
}

TEST(OptimizationSummary, TheHistoryPlotsTheObjectiveAndDistancePerIteration)
{
  const auto plot = optimization_history("iteration,stage,objective,distance,curvature\n"
                                         "1,1,4.5,4,0.5\n"
                                         "2,1,2.25,2,0.25\n"
                                         "3,1\n"); // a row cut short is left out
  ASSERT_TRUE(plot);
  ASSERT_EQ(plot->series.size(), 2u);
  ASSERT_EQ(plot->series[0].second.size(), 2u);
  EXPECT_EQ(plot->series[0].second[1], Eigen::Vector2d(2, 2.25));
  EXPECT_EQ(plot->series[1].second[0], Eigen::Vector2d(1, 4));
  EXPECT_FALSE(optimization_history("iteration,objective\n1,2\n")); // no distance column
  EXPECT_FALSE(optimization_history("iteration,objective,distance\n"));
}

const Json kCollide = Json::parse(R"({
  "clearance_mm": 0.5, "rounds": 2, "reoptimized": false, "min_bend_radius_mm": 12,
  "smallest_clearance_mm": {"before": 0.1, "after": 0.52},
  "targets": {"bend": {"before": {"rmse_mm": 1, "max_error_mm": 2},
                       "after": {"rmse_mm": 1.1, "max_error_mm": 2.2, "surface_rmse_mm": 0.3,
                                 "surface_max_error_mm": 0.9},
                       "rmse_change_percent": 10}},
  "collisions": [{"between": ["m1", "m2"], "clearance_mm": 0.1, "at_mm": [1, 2.25, 3]}],
  "moves_mm": {"m1": {"points": [0, 0.25], "tangents": [0.5]}},
  "bends": {"m1": {"min_bend_radius_mm": 20.5, "along_mm": 31.25, "at_mm": [1, 2, 3]}, "m2": {}}
})");

TEST(BehaviourSummary, TheTablesGiveErrorsCollisionsMovesAndBends)
{
  const std::vector<ReportTable> t = behaviour_tables(kCollide);
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t[0].rows.at(0),
            (std::vector<std::string>{"bend", "1.000", "1.100", "+10.0 %", "2.000", "2.200", "0.300", "0.900"}));
  EXPECT_EQ(t[1].rows.at(0), (std::vector<std::string>{"m1 and m2", "0.100", "(1.0, 2.2, 3.0)"}));
  EXPECT_EQ(t[2].title, "Collide: smallest clearance 0.100 → 0.520 mm (asked 0.500 mm); 2 round(s)");
  EXPECT_EQ(t[2].rows.at(0), (std::vector<std::string>{"m1", "0.250", "0.500"}));
  EXPECT_EQ(t[3].rows.at(0), (std::vector<std::string>{"m1", "20.500", "(1.000, 2.000, 3.000)", "31.250"}));
  EXPECT_EQ(t[3].rows.at(1), (std::vector<std::string>{"m2", "straight", "", ""}));
}

TEST(BehaviourSummary, ReadmeGivesEachRoutesTightestBend)
{
  const std::string text = muscle_bends_text(kCollide);
  EXPECT_NE(text.find("no tighter than 12.0 mm"), std::string::npos) << text;
  EXPECT_NE(text.find("  m1: 20.5 mm, 31.2 mm along it\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  m2: straight\n"), std::string::npos) << text;
  EXPECT_EQ(muscle_bends_text(Json::parse(R"({"clearance_mm": 0.5})")), "");
}

TEST(BehaviourSummary, PosesToCompareLeaveOutWhatStaysPut)
{
  const Json poses = Json::parse(R"([
    {"place": "curve c, first point", "translation_mm": [0.1, 0, 0], "rotation_deg": 1,
     "rotation_axis": [0, 0, 1]},
    {"place": "pose[1]", "translation_mm": [3, 4, 0], "rotation_deg": 30, "rotation_axis": [0, 1, 0],
     "rest_mm": [10, 0, 5], "nodes": 12, "asked_rotation_deg": 35, "rotation_about_asked_axis_deg": 29.96}])");
  EXPECT_EQ(poses_to_compare(poses),
            "    pose[1] (at (10.0, 0.0, 5.0) mm at rest: the centre of its 12 nodes): moves 5.0 mm (3.0, 4.0,\n"
            "      0.0) and turns 30.0° about (0.00, 1.00, 0.00); 30.0° about the axis asked (asked 35.0°)\n");
  EXPECT_EQ(poses_to_compare(Json::array({poses[0]})), "    nothing moves more than 0.5 mm or turns more than 5°\n");
}

} // namespace
} // namespace fibermold

// The sweep's summary read as a person comparing cases reads it: a pose target's turn reached, how
// each optimization ended, each case's report, ties all marked best, string values without quotes.
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "make/runner.hpp"
#include "sweep/sweep_plan.hpp"
#include "sweep/sweep_summary.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;

/// A case's built outputs as the stages write them: a pose target "curl" whose two regions turned
/// `reached` % and `other` % of their angle, at `rmse` mm, the optimizer ended by `termination`.
void built_case(const std::filesystem::path& dir, double rmse, double reached, double other,
                const std::string& termination)
{
  for (const char* stage : {"optimize", "collide", "export"})
    test::write_text(Runner::stamp_path(dir, stage), "{\"seconds\": 1.5}");
  test::write_text(dir / "optimize" / "report.json", "{\"termination\": \"" + termination + "\"}");
  test::write_text(dir / "collide" / "report.json",
                   "{\"targets\": {\"curl\": {\"after\": {\"rmse_mm\": " + std::to_string(rmse) +
                       ", \"max_error_mm\": 5.0}, \"poses\": [{\"place\": \"pose[1]\", \"rotation_reached_percent\": " +
                       std::to_string(reached) +
                       "}, {\"place\": \"pose[2]\", \"rotation_reached_percent\": " + std::to_string(other) + "}]}}}");
  test::write_text(dir / "export" / "report.html", "<html></html>");
}

TEST(SweepSummary, APoseTargetsTurnHowEachOptimizationEndedAndEachReportAreSideBySide)
{
  test::TempDir build;
  SweepPlan plan;
  plan.name = "presets";
  plan.axes = {"material.preset"};
  plan.stages = {"optimize", "collide", "export"};
  plan.cases = {{"aaaaaaaaaa", {"\"dragon-skin-10\""}, ""},
                {"bbbbbbbbbb", {"\"ecoflex-00-30\""}, ""},
                {"cccccccccc", {"\"dragon-skin-20\""}, ""}};
  // A new user's sweep: the case of least RMSE turned less of its angle than another, and one stopped
  // at the iteration limit; two cases tie (they shared one optimization).
  built_case(plan.case_dir(build.path(), "aaaaaaaaaa"), 3.29, 81.3, 90.0, "converged");
  built_case(plan.case_dir(build.path(), "bbbbbbbbbb"), 3.37, 95.0, 85.3, "iteration limit");
  built_case(plan.case_dir(build.path(), "cccccccccc"), 3.29, 81.3, 90.0, "converged");
  write_sweep_summary(plan, build.path());

  std::istringstream csv(test::read_text(build / "summary.csv"));
  std::string header, a, b, c;
  std::getline(csv, header);
  std::getline(csv, a);
  std::getline(csv, b);
  std::getline(csv, c);
  EXPECT_EQ(header, "case,material.preset,curl RMSE mm,curl max mm,curl turn reached %,optimizer,optimize s,collide "
                    "s,export s,report,best for");
  // The least-turned region's share; the preset without its TOML quotes; both tied cases best.
  EXPECT_EQ(a, "aaaaaaaaaa,dragon-skin-10,3.29,5,81.3,converged,1.5,1.5,1.5,cases/aaaaaaaaaa/export/report.html,curl");
  EXPECT_EQ(b, "bbbbbbbbbb,ecoflex-00-30,3.37,5,85.3,iteration limit,1.5,1.5,1.5,cases/bbbbbbbbbb/export/report.html,");
  EXPECT_TRUE(c.ends_with(",curl")) << c;
  const std::string html = test::read_text(build / "summary.html");
  EXPECT_THAT(html, HasSubstr("<td class=\"text\">ecoflex-00-30</td>"));
  EXPECT_THAT(html, HasSubstr("<td class=\"text\">iteration limit</td>"));
  EXPECT_THAT(html, HasSubstr("<a href=\"cases/bbbbbbbbbb/export/report.html\">report.html</a>"));
  std::size_t best = 0;
  for (std::size_t at = html.find("class=\"best\""); at != std::string::npos; at = html.find("class=\"best\"", at + 1))
    ++best;
  EXPECT_EQ(best, 2u); // the two tied cells
}

} // namespace
} // namespace fibermold

// The fibermold command line, run as a user runs it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

TEST(Cli, HelpListsTheCommands)
{
  const auto r = test::run_fibermold("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* command : {"make", "status", "clean", "check", "simulate"}) EXPECT_THAT(r.out, HasSubstr(command));
}

TEST(Cli, BadCommandLineExits2)
{
  EXPECT_EQ(test::run_fibermold("").exit_code, 2);
  EXPECT_EQ(test::run_fibermold("frobnicate").exit_code, 2);
  EXPECT_EQ(test::run_fibermold("make --no-such-flag").exit_code, 2);
}

TEST(Cli, CheckAcceptsTheBundledDemo)
{
  const auto r = test::run_fibermold("check");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("twisting-bar"));
}

TEST(Cli, CheckNamesMisspelledKeyLineAndClosestKey)
{
  test::TempDir dir;
  fs::copy_file(fs::path(FIBERMOLD_SOURCE_DIR) / "examples/twisting-bar/bar.stl", dir / "bar.stl");
  test::write_text(dir / "bad.toml", "[design]\nsurface = \"bar.stl\"\n\n[mold]\nwall = 4.0\nvoxle = 0.2\n");
  const auto r = test::run_fibermold("check bad.toml", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr((dir / "bad.toml").string() + ":6:1: [mold].voxle: unknown key 'voxle' in [mold]; "
                                                             "did you mean 'voxel'?"));
}

TEST(Cli, MissingDesignFileExits2)
{
  test::TempDir dir;
  const auto r = test::run_fibermold("check nope.toml", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("nope.toml: design file not found"));
}

TEST(Cli, AWordThatIsNoStageIsTheDesign)
{
  test::TempDir dir;
  auto r = test::run_fibermold("check typo_design", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("typo_design: design file not found"));
  r = test::run_fibermold("make st/nonexistent mesh", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("st/nonexistent: design file not found"));
}

} // namespace
} // namespace fibermold

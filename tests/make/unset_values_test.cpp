// The runner's check that no output holds a NaN, an infinity or a JSON null.
#include <algorithm>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "make/unset_values.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;

TEST(UnsetValues, AValueFmtPrintsForANanIsFoundWithItsLine)
{
  const auto found = unset_value("Muscles (3.0 mm):\na socket 4.0 mm wide reaching nan mm beyond the skin\n", false);
  ASSERT_TRUE(found);
  EXPECT_EQ(*found, "line 2: \"a socket 4.0 mm wide reaching nan mm beyond the skin\"");
  // Cut at 40 bytes either side, between characters (° is two bytes).
  const std::string degrees(30, 'x');
  EXPECT_EQ(unset_value("°°°°°°°°°°°°°°°°°°°°°°°°° turns nan° " + degrees + "°°°°°°°", false).value_or(""),
            "line 1: \"…°°°°°°°°°°°°°°°°° turns nan° " + degrees + "°°°°…\"");
  EXPECT_TRUE(unset_value("turns -nan° about it", false));
  EXPECT_TRUE(unset_value("[1.0, inf, 2]", false));
  EXPECT_TRUE(unset_value("-inf", false));
  EXPECT_TRUE(unset_value("{\"rmse_mm\": null}", true));
}

// What a stage's view of the design gives a key it did not declare (design_view.hpp).
TEST(UnsetValues, ADesignValueTheStageDidNotDeclareIsFound)
{
  EXPECT_THAT(unset_value("fibermold mold parts for \"<undeclared design.name>\"\n", false).value_or(""),
              HasSubstr("line 1: \"fibermold mold parts for \"<undeclared design.name>"));
  EXPECT_TRUE(unset_value("samples: -2147483648", false));
  EXPECT_FALSE(unset_value("samples: -214748364, 2147483647", false));
}

TEST(UnsetValues, WordsThatHoldThemAndScriptCodeAreNotValues)
{
  EXPECT_FALSE(unset_value("info: the nanometre scale, infill 15 %, nullable, financial, Infinity", true));
  EXPECT_FALSE(unset_value("if (painted === null) { x = NaN; }", false)); // report.html's script
  EXPECT_TRUE(unset_value("if (painted === null) {}", true));             // but not in JSON
  EXPECT_FALSE(unset_value("", true));
  EXPECT_FALSE(unset_value("nanx inf_ _null", true));
}

// A user's names and paths may hold the words (a reviewer's examples): they are not values.
TEST(UnsetValues, TheUsersOwnNamesAndPathsAndEncodedMeshesAreNotValues)
{
  const std::vector<std::string> own{"/afs/inf.ed.ac.uk/user/s1/robot.stl", "inf-gripper", "/tmp/null/out"};
  EXPECT_FALSE(unset_value("{\"file\": \"/afs/inf.ed.ac.uk/user/s1/robot.stl\"}", true, own));
  EXPECT_FALSE(unset_value("fibermold mold parts for \"inf-gripper\"\n", false, own));
  EXPECT_FALSE(unset_value("--build-dir /tmp/null/out\n", true, own));
  // The same words elsewhere still are.
  EXPECT_TRUE(unset_value("{\"file\": \"/afs/inf.ed.ac.uk/user/s1/robot.stl\", \"rmse\": null}", true, own));
  EXPECT_TRUE(unset_value("inf-gripper turns inf°", false, own));
  EXPECT_TRUE(unset_value("/afs/inf.ed.ac.uk/user/s1/robot.stl", false)); // not said to be the user's: a value
  // Base64 that spells a word between '+' and '/' (report.html's meshes: about once in 10⁹ bytes).
  const std::string base64 = "AAAAQUJDREVGR0hJSktMTU5PUFFSU1RVVldY+nan/WVphYmNkZWZnaGlqa2xtbm9wcXJzdHV2d3h5eg==";
  EXPECT_FALSE(unset_value("const mesh = \"" + base64 + "\";", false));
  EXPECT_TRUE(unset_value("const x = [1.0, nan, 2.0];", false)); // numbers in a script are still read
  // An undeclared value as report.html escapes it.
  EXPECT_TRUE(unset_value("<td>&lt;undeclared fiber.name&gt;</td>", false));
}

TEST(UnsetValues, TheUsersTextIsTheDesignsNamesAndPaths)
{
  Design d;
  d.file = "/home/nan/robots/design.toml";
  d.design.name = "inf-gripper";
  d.design.surface = "/home/nan/robots/body.stl";
  Fiber f;
  f.name = "null-flexor";
  d.fibers.push_back(f);
  const std::vector<std::string> own = own_text(d, "out");
  for (const char* s :
       {"/home/nan/robots/design.toml", "/home/nan/robots", "body.stl", "inf-gripper", "null-flexor", "out"})
    EXPECT_NE(std::find(own.begin(), own.end(), s), own.end()) << s;
}

TEST(UnsetValues, FilesAreReadByKind)
{
  test::TempDir dir;
  test::write_text(dir / "report.json", "{\"a\": null}");
  test::write_text(dir / "report.html", "<script>let drag = null;</script>");
  test::write_text(dir / "deformed.vtu", "<DataArray>0 nan 1</DataArray>");
  test::write_text(dir / "part.stl", "solid nan"); // binary kinds are not read
  EXPECT_TRUE(unset_value_in(dir / "report.json"));
  EXPECT_FALSE(unset_value_in(dir / "report.html"));
  EXPECT_THAT(unset_value_in(dir / "deformed.vtu").value_or(""), HasSubstr("line 1"));
  EXPECT_FALSE(unset_value_in(dir / "part.stl"));
}

} // namespace
} // namespace fibermold

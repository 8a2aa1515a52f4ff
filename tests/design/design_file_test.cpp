#include "design/design_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

const char* kMinimal = R"(
[design]
surface = "body.stl"
)";

class DesignFileTest : public ::testing::Test {
protected:
  void SetUp() override { test::write_text(dir_ / "body.stl", "solid x\nendsolid x\n"); }

  Design parse(const std::string& text) { return parse_design(text, dir_ / "design.toml"); }

  /// The problems reported for `text`; fails the test when it parses.
  std::vector<Diagnostic> problems(const std::string& text)
  {
    try {
      parse(text);
    } catch (const InputError& e) {
      return e.diagnostics();
    }
    ADD_FAILURE() << "expected an InputError for:\n" << text;
    return {};
  }

  /// The one problem reported for `text`, formatted.
  std::string problem(const std::string& text)
  {
    auto p = problems(text);
    EXPECT_EQ(p.size(), 1u);
    return p.empty() ? "" : p.front().to_string();
  }

  test::TempDir dir_;
};

TEST_F(DesignFileTest, DemoParsesIntoSIUnits)
{
  const Design d = load_design(fs::path(FIBERMOLD_SOURCE_DIR) / "examples/twisting-bar/design.toml");
  EXPECT_EQ(d.design.name, "twisting-bar");
  EXPECT_EQ(d.design.surface, fs::path(FIBERMOLD_SOURCE_DIR) / "examples/twisting-bar/bar.stl");
  EXPECT_DOUBLE_EQ(d.design.surface_scale, 1e-3);
  EXPECT_DOUBLE_EQ(d.material.youngs_modulus, 86.4e3);
  EXPECT_DOUBLE_EQ(*d.mesh.edge_length, 10.0e-3);
  EXPECT_DOUBLE_EQ(d.muscle.model.diameter, 3.0e-3);
  EXPECT_DOUBLE_EQ(d.muscle.max_pressure, 425e3);
  ASSERT_EQ(d.fibers.size(), 1u);
  ASSERT_EQ(d.fibers[0].points.size(), 6u);
  EXPECT_DOUBLE_EQ(d.fibers[0].points[5].x(), 0.129);
  ASSERT_EQ(d.targets.size(), 1u);
  ASSERT_EQ(d.targets[0].loads.size(), 1u);
  EXPECT_DOUBLE_EQ(d.targets[0].loads[0].torque->x(), 0.00452);
  EXPECT_DOUBLE_EQ((*d.targets[0].loads[0].region.box)[0].x(), 0.127);
  EXPECT_EQ(d.optimize.max_iterations, 1000);
  EXPECT_EQ(d.optimize.route_only_iterations, 30);
  EXPECT_DOUBLE_EQ(d.mold.block.wall, 4e-3);
  EXPECT_DOUBLE_EQ(d.mold.voxel, 0.2e-3);
  EXPECT_DOUBLE_EQ(d.export_.printer_volume.x(), 0.25);
}

TEST_F(DesignFileTest, DefaultsFillEverySectionAndAreRecorded)
{
  const Design d = parse(kMinimal);
  EXPECT_EQ(d.design.name, dir_.path().filename().string()); // design.toml: named after its folder
  EXPECT_EQ(d.sim.basis, BasisKind::mls_linear);
  EXPECT_DOUBLE_EQ(d.sim.mls_radius, 1.7);
  EXPECT_FALSE(d.mesh.edge_length.has_value());
  EXPECT_DOUBLE_EQ(d.material.poisson_ratio, 0.47);
  EXPECT_DOUBLE_EQ(d.material.gravity.z(), -9.81);
  EXPECT_DOUBLE_EQ(d.collide.clearance, 1e-3);
  EXPECT_DOUBLE_EQ(d.muscle.segments_per_length, 500.0);
  EXPECT_DOUBLE_EQ(d.muscle.model.stiffness.slope_low, -549.92);
  EXPECT_FALSE(d.mold.parting.has_value());
  // The runner hashes effective values, so a default written out explicitly changes nothing.
  EXPECT_EQ(d.values.at("[mold].wall"), "4");
  EXPECT_EQ(d.values.at("[mold].parting"), "\"auto\"");
  EXPECT_EQ(d.values.at("[mesh].edge_length"), "auto");
  const Design explicit_default = parse(std::string(kMinimal) + "[mold]\nwall = 4.0\n");
  EXPECT_EQ(explicit_default.values, d.values);
}

TEST_F(DesignFileTest, RelativePathsResolveAgainstTheDesignFolder)
{
  test::write_text(dir_ / "shapes" / "body.obj", "o x\n");
  const Design d = parse_design("[design]\nsurface = \"../shapes/body.obj\"\n", dir_ / "sub" / "design.toml");
  EXPECT_EQ(d.design.surface, dir_.path() / "shapes" / "body.obj");
}

TEST_F(DesignFileTest, MisspelledKeyNamesLineAndClosestKey)
{
  const std::string message = problem(std::string(kMinimal) + "[mold]\nwal = 4.0\n");
  EXPECT_THAT(message, HasSubstr((dir_ / "design.toml").string() + ":5:1: [mold].wal: unknown key 'wal'"));
  EXPECT_THAT(message, HasSubstr("did you mean 'wall'?"));
}

TEST_F(DesignFileTest, MisspelledSectionSuggestsArrayOfTables)
{
  EXPECT_THAT(problem(std::string(kMinimal) + "[[fibre]]\nname = \"a\"\n"), HasSubstr("did you mean [[fiber]]?"));
  EXPECT_THAT(problem(std::string(kMinimal) + "[colide]\n"), HasSubstr("did you mean [collide]?"));
  EXPECT_THAT(problem(std::string(kMinimal) + "[fiber]\nname = \"a\"\n"), HasSubstr("write [[fiber]]"));
}

TEST_F(DesignFileTest, WrongTypesAndRangesNameKeyLineAndBound)
{
  EXPECT_THAT(problem(std::string(kMinimal) + "[mold]\nkeys = \"four\"\n"),
              HasSubstr(":5:8: [mold].keys: expected an integer, got a string"));
  EXPECT_THAT(problem(std::string(kMinimal) + "[mold]\nwall = -1\n"),
              HasSubstr("[mold].wall: must be in (0, 1000] mm, got -1"));
  EXPECT_THAT(problem(std::string(kMinimal) + "[material]\npoisson_ratio = 0.5\n"),
              HasSubstr("[material].poisson_ratio: must be in [0, 0.5)"));
  EXPECT_THAT(problem(std::string(kMinimal) + "[sim]\nbasis = \"mls-linaer\"\n"),
              HasSubstr("did you mean \"mls-linear\"?"));
  EXPECT_THAT(problem(std::string(kMinimal) + "[mold]\npull = [0, 0]\n"), HasSubstr("expected three numbers"));
  EXPECT_THAT(problem(std::string(kMinimal) + "[mold]\npull = [0, 0, 0]\n"), HasSubstr("must not be the zero vector"));
  EXPECT_THAT(problem(std::string(kMinimal) + "[sim]\nquadrature_points = 5\n"), HasSubstr("must be 1, 4 or 8"));
  // An integer no double holds exactly (toml++ gives none for it): rounded, then out of range, not
  // an empty optional dereferenced into garbage.
  EXPECT_THAT(problem(std::string(kMinimal) + "[material]\npoisson_ratio = 9223372036854775807\n"),
              HasSubstr(":5:17: [material].poisson_ratio: must be in [0, 0.5), got 9.223372036854776e+18"));
}

TEST_F(DesignFileTest, MissingRequiredKeysAndFiles)
{
  EXPECT_THAT(problem("[mesh]\nrepair = true\n"), HasSubstr("[design].surface: missing; required"));
  EXPECT_THAT(problem("[design]\nsurface = \"nope.stl\"\n"), HasSubstr(":2:11: [design].surface: file not found"));
  EXPECT_THAT(problem(std::string(kMinimal) + "[[fiber]]\npoints = [[0,0,0],[1,0,0]]\n"),
              HasSubstr("[fiber.1].name: missing; required"));
  EXPECT_THAT(problem(std::string(kMinimal) + "[[fiber]]\nname = \"m\"\npoints = [[0,0,0]]\n"),
              HasSubstr("[fiber.m].points: needs at least 2 points, got 1"));
}

TEST_F(DesignFileTest, EveryProblemIsReportedAtOnceInLineOrder)
{
  const auto p = problems(std::string(kMinimal) + "[mold]\nwal = 4\nkeys = -1\n[sim]\nbasis = 3\n");
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0].line, 5);
  EXPECT_EQ(p[1].line, 6);
  EXPECT_EQ(p[2].line, 8);
}

TEST_F(DesignFileTest, InvalidTomlNamesTheLine)
{
  EXPECT_THAT(problem("[design]\nsurface = \"body.stl\"\nname = \n"), HasSubstr(":3:"));
  EXPECT_THAT(problem("[design]\nsurface = \"body.stl\"\nname = \n"), HasSubstr("not valid TOML"));
  // A list without its "]": the parser stops on the next line; the message names the line that opened it.
  const std::string fiber = std::string(kMinimal) + "[[fiber]]\nname = \"m1\"\npoints = ";
  const int points_line = static_cast<int>(std::count(kMinimal, kMinimal + std::strlen(kMinimal), '\n')) + 3;
  const std::string opened = fmt::format("(the list opened at line {}, column 10 ", points_line);
  EXPECT_THAT(problem(fiber + "[[0, 0, 0], [9, 0, 0]\n[mold]\n"),
              HasSubstr(opened + "is still open here: a ',' between its entries or its closing ']' is missing)"));
  // A comma missing between two points on lines of their own: the same words, which name both fixes.
  EXPECT_THAT(problem(fiber + "[[0, 0, 0],\n  [5, 0, 0]\n  [9, 0, 0]]\n"), HasSubstr(opened + "is still open here"));
  // Left open at the end of the file.
  EXPECT_THAT(problem(fiber + "[[0, 0, 0], [9, 0, 0]\n"), HasSubstr(opened + "is never closed: its ']' is missing)"));
  // A dangling comma or an empty entry is no unclosed list: no such words.
  EXPECT_THAT(problem(fiber + "[[0, 0, 0],, [9, 0, 0]]\n"), Not(HasSubstr("opened at")));
  EXPECT_THAT(problem(std::string(kMinimal) + "[mold]\nbox = { wall = 4, }\n"), Not(HasSubstr("opened at")));
}

TEST_F(DesignFileTest, TargetsAreCheckedByKind)
{
  const std::string fiber = "[[fiber]]\nname = \"m1\"\npoints = [[0,0,0],[10,0,0]]\n";
  const Design d = parse(std::string(kMinimal) + fiber +
                         "[[target]]\nname = \"t\"\nkind = \"fibers\"\nfibers = [{ name = \"m1\", pressure = 300 }]\n");
  ASSERT_EQ(d.targets[0].fibers.size(), 1u);
  EXPECT_DOUBLE_EQ(d.targets[0].fibers[0].pressure, 300e3);

  EXPECT_THAT(problem(std::string(kMinimal) + fiber +
                      "[[target]]\nname = \"t\"\nkind = \"fibers\"\nfibers = [{ name = \"m1\", pressure = 500 }]\n"),
              HasSubstr("pressure: must be in [0, 425] kPa, got 500"));
  EXPECT_THAT(problem(std::string(kMinimal) +
                      "[[target]]\nname = \"t\"\nkind = \"fibers\"\nfibers = [{ name = \"m9\", pressure = 5 }]\n"),
              HasSubstr("no [[fiber]] named \"m9\""));
  EXPECT_THAT(problem(std::string(kMinimal) + "[[target]]\nname = \"t\"\nkind = \"forces\"\n"),
              HasSubstr("[target.t].load: missing; required"));
  EXPECT_THAT(problem(std::string(kMinimal) +
                      "[[target]]\nname = \"t\"\nkind = \"forces\"\nload = [{ point = [0,0,0], torque = [1,0,0] }]\n"),
              HasSubstr("a point load takes a force, not a torque"));
  EXPECT_THAT(problem(std::string(kMinimal) +
                      "[[target]]\nname = \"t\"\nkind = \"forces\"\n"
                      "load = [{ box = { min = [0,0,0], max = [1,1,1] }, vertices = [1], force = [1,0,0] }]\n"),
              HasSubstr("give exactly one of box"));
}

TEST_F(DesignFileTest, TargetActuatorsNameFibers)
{
  const std::string fibers = "[[fiber]]\nname = \"a\"\npoints = [[0,0,0],[10,0,0]]\n"
                             "[[fiber]]\nname = \"b\"\npoints = [[0,1,0],[10,1,0]]\n";
  const std::string target =
      "[[target]]\nname = \"t\"\nkind = \"forces\"\nload = [{ point = [0,0,0], force = [1,0,0] }]\n";
  const Design d = parse(std::string(kMinimal) + fibers + target + "actuators = [\"b\"]\n");
  EXPECT_EQ(d.targets[0].actuators, std::vector<std::string>{"b"});
  EXPECT_EQ(d.values.at("[target.t].actuators"), "[\"b\"]");
  EXPECT_TRUE(parse(std::string(kMinimal) + fibers + target).targets[0].actuators.empty());
  EXPECT_THAT(problem(std::string(kMinimal) + fibers + target + "actuators = [\"c\"]\n"),
              HasSubstr("[target.t].actuators: expected the name of a [[fiber]]"));
  EXPECT_THAT(
      problem(std::string(kMinimal) + fibers + target + "actuators = [\"a\"]\n[optimize]\nstrategy = \"sequential\"\n"),
      HasSubstr("the sequential strategy assigns fiber k to target k"));
}

TEST_F(DesignFileTest, NamesMustBeSafeFileNames)
{
  EXPECT_THAT(problem("[design]\nsurface = \"body.stl\"\nname = \"..\"\n"),
              HasSubstr(":3:8: [design].name: \"..\" cannot name a file"));
  EXPECT_THAT(problem("[design]\nsurface = \"body.stl\"\nname = \"/tmp/x\"\n"), HasSubstr("cannot name a file"));
  EXPECT_THAT(problem(std::string(kMinimal) +
                      "[[target]]\nname = \"a/b\"\nkind = \"forces\"\nload = [{ point = [0,0,0], force = [1,0,0] }]\n"),
              HasSubstr("[target.a/b].name: \"a/b\" cannot name a file"));
}

TEST_F(DesignFileTest, EffectiveValuesAreRecordedNormalised)
{
  const Design a = parse(std::string(kMinimal) + "[mold]\npull = [0, 0, 2]\n");
  const Design b = parse_design("[design]\nsurface = \"./body.stl\"\n[mold]\npull = [0, 0, 1]\n", dir_ / "design.toml");
  EXPECT_EQ(a.values, b.values);
}

TEST_F(DesignFileTest, MuscleModelMustStayMeaningful)
{
  EXPECT_THAT(problem(std::string(kMinimal) + "[muscle]\nstiffness = [[1, 2], [1, 3]]\n"),
              HasSubstr("[muscle].stiffness: the two lines are parallel and distinct"));
  EXPECT_THAT(problem(std::string(kMinimal) + "[muscle]\nmax_pressure = 2500\n"),
              HasSubstr("[muscle].max_pressure: at 2500 kPa the muscle would contract by more than 95 %"));
  // The documented default, written out, is taken (its intercept is 4.07e9 Pa; the bound was 1e9).
  const Design d = parse(std::string(kMinimal) + "[muscle]\ntaut = [[-23.91e3, 4067.66e6], [-986.60, 833.51e6]]\n");
  EXPECT_EQ(d.muscle.model.taut.intercept_low, MuscleParameters{}.taut.intercept_low);
  EXPECT_THAT(problem(std::string(kMinimal) + "[muscle]\ntaut = [[1, 2e12], [2, 3]]\n"),
              HasSubstr("[muscle].taut: every coefficient must be in [-1e12, 1e12]"));
}

TEST_F(DesignFileTest, NamesMustBeUnique)
{
  const std::string fiber = "[[fiber]]\nname = \"m1\"\npoints = [[0,0,0],[10,0,0]]\n";
  EXPECT_THAT(problem(std::string(kMinimal) + fiber + fiber),
              HasSubstr(":8:8: [fiber.m1]: the name \"m1\" is used twice"));
}

TEST_F(DesignFileTest, MoldWallBelowPrinterMinimumIsRejected)
{
  EXPECT_THAT(problem(std::string(kMinimal) + "[mold]\nwall = 0.5\n[export]\nmin_wall = 0.8\n"),
              HasSubstr("[mold].wall: 0.5 mm is below the printer's minimum wall"));
}

TEST_F(DesignFileTest, PartingPlaneAndFormats)
{
  const Design d =
      parse(std::string(kMinimal) +
            "[mold]\nparting = { point = [0, 0, 5], normal = [0, 0, 2] }\n[export]\nformats = [\"stl\", \"3mf\"]\n");
  ASSERT_TRUE(d.mold.parting.has_value());
  EXPECT_DOUBLE_EQ(d.mold.parting->point.z(), 5e-3);
  EXPECT_DOUBLE_EQ(d.mold.parting->normal.z(), 1.0);
  EXPECT_EQ(d.export_.formats, (std::vector<std::string>{"stl", "3mf"}));
  EXPECT_THAT(problem(std::string(kMinimal) + "[export]\nformats = [\"stp\"]\n"), HasSubstr("unknown format"));
}

/// docs/design-file.md's "Ranges" table, row by row for the keys of plain sections: just outside
/// each bound is refused at its line, naming the bound as the table gives it; just inside is taken.
TEST_F(DesignFileTest, EveryDocumentedRangeIsTheOneChecked)
{
  const std::string doc = test::read_text(fs::path(FIBERMOLD_SOURCE_DIR) / "docs" / "design-file.md");
  const std::regex row(R"(\| `\[(material|mesh|sim|muscle|optimize|collide|mold|export)\] (\w+)` \| )"
                       R"(([\[(])(-?[0-9.e]+), (-?[0-9.e]+)([\])]) \|)");
  int rows = 0;
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), row); it != std::sregex_iterator(); ++it, ++rows) {
    const std::smatch& m = *it;
    const std::string section = m[1], key = m[2];
    const double lo = std::stod(m[4]), hi = std::stod(m[5]);
    const bool lo_open = m[3] == "(", hi_open = m[6] == ")";
    const auto text = [&](double v) { return fmt::format("{}[{}]\n{} = {}\n", kMinimal, section, key, v); };
    const bool integer = std::floor(lo) == lo && std::floor(hi) == hi && hi - lo >= 8 && hi <= 1e8 &&
                         (key == "max_tets" || key.find("iterations") != std::string::npos || key == "keys" ||
                          key == "vents" || key == "screw_holes" || key == "starts");
    const double step = integer ? 1 : std::max(std::abs(hi - lo), 1.0) * 1e-6;
    const double below = lo_open ? lo : lo - step, above = hi_open ? hi : hi + step;
    for (const double bad : {below, above}) {
      const std::string p = problem(
          integer ? fmt::format("{}[{}]\n{} = {}\n", kMinimal, section, key, static_cast<long long>(bad)) : text(bad));
      EXPECT_THAT(p, HasSubstr(fmt::format(":5:{}: [{}].{}: must be", key.size() + 4, section, key))) << p;
      if (!integer) {
        EXPECT_THAT(p, HasSubstr(fmt::format("{}{}, {}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]"))) << p;
      }
    }
    // Inside: the geometric mean of positive bounds (a value from the middle of a range of decades),
    // else up to 1 (a larger one would meet the checks between keys: a min_wall above the wall).
    const double inside = lo > 0 ? std::sqrt(lo * hi) : hi_open ? (lo + hi) / 2 : std::min(hi, 1.0);
    const std::string ok =
        integer ? fmt::format("{}[{}]\n{} = {}\n", kMinimal, section, key, static_cast<long long>(std::round(inside)))
                : text(inside);
    EXPECT_NO_THROW(parse(ok)) << ok;
  }
  EXPECT_GE(rows, 40);
}

/// The numbers in a default or value: "[0, 0, -9.81]" → {0, 0, -9.81}; "\"mm\"" → {} (text).
std::vector<double> numbers_in(const std::string& text)
{
  std::vector<double> out;
  const std::regex number(R"(-?[0-9]+(\.[0-9]+)?(e-?[0-9]+)?)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), number); it != std::sregex_iterator(); ++it)
    out.push_back(std::stod(it->str()));
  return out;
}

/// docs/design-file.md's key tables, row by row for the plain sections: each default written as a
/// value (a number, a list of numbers, a quoted string, true or false) is the one the code takes
/// when the key is left out.
TEST_F(DesignFileTest, EveryDocumentedDefaultIsTheOneTheCodeTakes)
{
  const std::string doc = test::read_text(fs::path(FIBERMOLD_SOURCE_DIR) / "docs" / "design-file.md");
  const Design d = parse(kMinimal);
  const std::regex heading(R"(^## \[(\w+)\]$)"), row(R"(^\| `(\w+)` \|[^|]*\| *([^|]*[^| ]) *\|)");
  std::string section;
  int checked = 0;
  std::istringstream lines(doc);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_match(line, m, heading)) {
      section = m[1];
      continue;
    }
    if (line.starts_with("## ")) section.clear(); // an array section, or the end of the keys
    if (section.empty() || !std::regex_search(line, m, row)) continue;
    const std::string key = fmt::format("[{}].{}", section, std::string(m[1]));
    std::string documented = m[2];
    documented.erase(documented.find_last_not_of(' ') + 1);
    const bool text = documented.starts_with("`\"") && documented.ends_with("\"`");
    const bool flag = documented == "false" || documented == "true";
    const bool number =
        !numbers_in(documented).empty() && documented.find_first_not_of("0123456789.e-[], ") == std::string::npos;
    if (!text && !flag && !number) continue; // "auto", "**required**", a sentence
    ASSERT_TRUE(d.values.contains(key)) << key << " is documented but the code records no such key";
    const std::string value = d.values.at(key);
    if (text)
      EXPECT_EQ(value, documented.substr(1, documented.size() - 2)) << key;
    else if (flag)
      EXPECT_EQ(value, documented) << key;
    else {
      const std::vector<double> want = numbers_in(documented), got = numbers_in(value);
      ASSERT_EQ(want.size(), got.size()) << key << ": documented " << documented << ", the code's " << value;
      for (std::size_t i = 0; i < want.size(); ++i)
        EXPECT_NEAR(got[i], want[i], 1e-9 * std::abs(want[i]))
            << key << ": documented " << documented << ", the code's " << value;
    }
    ++checked;
  }
  EXPECT_GE(checked, 50);
}

TEST_F(DesignFileTest, CoordinatesStringsAndNamesHaveLimits)
{
  const std::string fiber = std::string(kMinimal) + "[[fiber]]\nname = \"m\"\npoints = [[0, 0, 0], [1e308, 0, 0]]\n";
  EXPECT_THAT(
      problem(fiber),
      HasSubstr(":6:22: [fiber.m].points[2]: every coordinate must be in [-10000, 10000] mm, got [1e+308, 0, 0]"));
  EXPECT_THAT(problem(std::string(kMinimal) + "[material]\ngravity = [0, 0, -1e4]\n"),
              HasSubstr("[material].gravity: every coordinate must be in [-1000, 1000] m/s²"));
  EXPECT_THAT(problem(std::string(kMinimal) + "[mold]\nparting = { point = [0, 0, 2e4], normal = [0, 0, 1] }\n"),
              HasSubstr("[mold].parting.point: every coordinate must be in [-10000, 10000] mm"));
  // A NUL would cut a path short, and a megabyte of value is not echoed back whole.
  EXPECT_THAT(problem("[design]\nsurface = \"body\\u0000.stl\"\n"),
              HasSubstr("[design].surface: \"body\" contains a NUL character"));
  const std::string huge(8 << 20, 'x');
  const std::string p = problem(std::string(kMinimal) + "[sim]\nbasis = \"" + huge + "\"\n");
  EXPECT_THAT(p, HasSubstr("(8388608 characters) is longer than 4096 characters"));
  EXPECT_LT(p.size(), 300u);
  EXPECT_THAT(problem("[design]\nsurface = \"body.stl\"\nname = \"" + std::string(101, 'a') + "\"\n"),
              HasSubstr("is longer than 100 characters: it names files and folders"));
  // A wrong value of a required choice is reported once, as wrong, not also as missing.
  const auto kind =
      problems(std::string(kMinimal) +
               "[[target]]\nname = \"t\"\nkind = \"Forces\"\nload = [{ point = [0, 0, 0], force = [1, 0, 0] }]\n");
  ASSERT_EQ(kind.size(), 1u);
  EXPECT_THAT(
      kind.front().to_string(),
      HasSubstr("unknown value \"Forces\"; expected one of: forces, surface, fibers, pose (did you mean \"forces\"?)"));
}

TEST(DesignKeyMatches, SectionAndKeyPrefixes)
{
  EXPECT_TRUE(design_key_matches("[mold].wall", "mold"));
  EXPECT_TRUE(design_key_matches("[mold].wall", "mold.wall"));
  EXPECT_FALSE(design_key_matches("[mold].wall", "mold.wal"));
  EXPECT_FALSE(design_key_matches("[molds].wall", "mold"));
  EXPECT_TRUE(design_key_matches("[fiber.m1].points", "fiber"));
  EXPECT_TRUE(design_key_matches("[target.t].load[1].box.min", "target"));
}

} // namespace
} // namespace fibermold

// A stage's view of the design (design/design_view.hpp): each row of the view's table copies the
// members its key sets, and a view holds an undeclared value (design/undeclared_value.hpp) in every
// member its stage did not declare.
#include "design/design_view.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include "design/design_file.hpp"
#include "design/undeclared_value.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

namespace fs = std::filesystem;

// Every member of a Design as text, named by its path in the structs ("mold.block.wall"): the test's
// own list of the members, against which the view's table is held.

std::string text(double v) { return fmt::format("{}", v); }
std::string text(int v) { return std::to_string(v); }
std::string text(bool v) { return v ? "true" : "false"; }
std::string text(const std::string& v) { return fmt::format("\"{}\"", v); }
std::string text(const fs::path& v) { return fmt::format("\"{}\"", v.string()); }
std::string text(const Vec3& v) { return fmt::format("[{}, {}, {}]", v.x(), v.y(), v.z()); }
std::string text(const TwoPieceLine& v);
std::string text(const PartingPlane& v);
std::string text(const Region& v);
std::string text(const FixedRegion& v);
std::string text(const Fiber& v);
std::string text(const TrackingCurve& v);
std::string text(const Load& v);
std::string text(const FiberActuation& v);
std::string text(const Pose& v);
std::string text(const Target& v);

template <typename E>
requires std::is_enum_v<E> std::string text(E v) { return std::to_string(static_cast<int>(v)); }

template <typename T> std::string text(const std::optional<T>& v);
template <typename T, std::size_t N> std::string text(const std::array<T, N>& v);
template <typename T> std::string text(const std::vector<T>& v);

template <typename T> std::string text(const std::optional<T>& v) { return v ? text(*v) : "none"; }

template <typename T, std::size_t N> std::string text(const std::array<T, N>& v)
{
  std::vector<std::string> items;
  for (const T& x : v) items.push_back(text(x));
  return fmt::format("[{}]", fmt::join(items, ", "));
}

template <typename T> std::string text(const std::vector<T>& v)
{
  std::vector<std::string> items;
  for (const T& x : v) items.push_back(text(x));
  return fmt::format("[{}]", fmt::join(items, ", "));
}

std::string text(const TwoPieceLine& v)
{
  return fmt::format("[[{}, {}], [{}, {}]]", v.slope_low, v.intercept_low, v.slope_high, v.intercept_high);
}
std::string text(const PartingPlane& v) { return text(v.point) + " " + text(v.normal); }
std::string text(const Region& v) { return text(v.box) + " " + text(v.vertices) + " " + text(v.point); }
std::string text(const FixedRegion& v) { return text(v.name) + " " + text(v.region); }
std::string text(const Fiber& v) { return text(v.name) + " " + text(v.points) + " " + text(v.tangents); }
std::string text(const TrackingCurve& v)
{
  return fmt::format("{} {} {} {} {}", text(v.name), text(v.points), v.samples, v.weight_position,
                     v.weight_orientation);
}
std::string text(const Load& v) { return text(v.region) + " " + text(v.force) + " " + text(v.torque); }
std::string text(const FiberActuation& v) { return text(v.name) + " " + text(v.points) + " " + text(v.pressure); }
std::string text(const Pose& v)
{
  return fmt::format("{} {} {} {} {}", text(v.region), text(v.axis), v.angle, text(v.about), text(v.translation));
}
std::string text(const Target& v)
{
  return fmt::format("{} {} {} {} {} {} {} {} {}", text(v.name), text(v.kind), text(v.loads), text(v.surface),
                     v.strain_penalty, text(v.fibers), text(v.poses), text(v.actuators), v.weight);
}

using Members = std::map<std::string, std::string>;

#define MEMBER(path) m[#path] = text(d.path)

/// [design], [material], [mesh], [sim], [muscle] and the array sections.
void body_members(const Design& d, Members& m)
{
  MEMBER(design.name);
  MEMBER(design.surface);
  MEMBER(design.units);
  MEMBER(design.surface_scale);
  MEMBER(material.model);
  MEMBER(material.preset);
  MEMBER(material.youngs_modulus);
  MEMBER(material.poisson_ratio);
  MEMBER(material.density);
  MEMBER(material.gravity);
  MEMBER(mesh.edge_length);
  MEMBER(mesh.radius_edge_ratio);
  MEMBER(mesh.min_dihedral_deg);
  MEMBER(mesh.max_tets);
  MEMBER(mesh.repair);
  MEMBER(mesh.surface_triangles);
  MEMBER(sim.basis);
  MEMBER(sim.mls_radius);
  MEMBER(sim.quadrature_points);
  MEMBER(fixed);
  MEMBER(muscle.model.stiffness);
  MEMBER(muscle.model.taut);
  MEMBER(muscle.model.rest_strain_slope);
  MEMBER(muscle.model.rest_strain_intercept);
  MEMBER(muscle.model.smoothing);
  MEMBER(muscle.model.diameter);
  MEMBER(muscle.max_pressure);
  MEMBER(muscle.min_bend_radius);
  MEMBER(muscle.segments_per_length);
  MEMBER(fibers);
  MEMBER(tracking_curves);
  MEMBER(targets);
}

/// [optimize], [collide], [mold] and [export]. mold.block.min_wall is left out: no key sets it (the
/// molds take [export] min_wall, two_shot_molds.hpp).
void process_members(const Design& d, Members& m)
{
  MEMBER(optimize.enabled);
  MEMBER(optimize.strategy);
  MEMBER(optimize.method);
  MEMBER(optimize.max_iterations);
  MEMBER(optimize.route_only_iterations);
  MEMBER(optimize.starts);
  MEMBER(optimize.gradient_tolerance);
  MEMBER(optimize.relative_tolerance);
  MEMBER(optimize.decrease_tolerance);
  MEMBER(optimize.weight_curvature);
  MEMBER(optimize.weight_skin_barrier);
  MEMBER(optimize.weight_bend_barrier);
  MEMBER(optimize.weight_pressure_barrier);
  MEMBER(optimize.refine);
  MEMBER(collide.clearance);
  MEMBER(collide.smoothness);
  MEMBER(collide.samples_per_length);
  MEMBER(collide.reoptimize);
  MEMBER(mold.block.wall);
  MEMBER(mold.block.keys);
  MEMBER(mold.block.key_shape);
  MEMBER(mold.block.key_diameter);
  MEMBER(mold.block.key_clearance);
  MEMBER(mold.block.sprue_diameter);
  MEMBER(mold.block.vents);
  MEMBER(mold.block.vent_diameter);
  MEMBER(mold.block.screw_holes);
  MEMBER(mold.block.screw_diameter);
  MEMBER(mold.voxel);
  MEMBER(mold.pull);
  MEMBER(mold.parting);
  MEMBER(mold.groove_clearance);
  MEMBER(mold.min_silicone);
  MEMBER(mold.end_channel_length);
  MEMBER(mold.end_channel_diameter);
  MEMBER(mold.draft_deg);
  MEMBER(mold.shrink);
  MEMBER(mold.labels);
  MEMBER(export_.formats);
  MEMBER(export_.printer_volume);
  MEMBER(export_.min_wall);
}

#undef MEMBER

Members members(const Design& d)
{
  Members m;
  body_members(d, m);
  process_members(d, m);
  return m;
}

/// Members as a list for a message: "mold.block.wall, mold.voxel", or "nothing".
std::string listed(const std::set<std::string>& members)
{
  return members.empty() ? "nothing" : fmt::format("{}", fmt::join(members, ", "));
}

/// The members whose text differs between `a` and `b`.
std::set<std::string> differing(const Members& a, const Members& b)
{
  std::set<std::string> out;
  for (const auto& [member, value] : a)
    if (b.at(member) != value) out.insert(member);
  return out;
}

// A design with every section, and per view part one edit of it that gives the part's key another
// value than it has there. The base gives the keys whose defaults follow others explicitly (a preset
// sets the stiffness and density, the diameter the bend radius), so that an edit sets one key.
const char* kBase = R"([design]
surface = "body.stl"
[material]
youngs_modulus = 86400
poisson_ratio = 0.47
density = 1070
[mesh]
[sim]
[muscle]
min_bend_radius = 6
[[fixed]]
box = { min = [-1, -9, -9], max = [0.5, 9, 9] }
[[fiber]]
name = "m1"
points = [[0, 0, 0], [30, 1, 0], [60, 0, 0]]
[[tracking_curve]]
points = [[0, 0, 0], [60, 0, 0]]
[[target]]
name = "s"
kind = "fibers"
fibers = [{ name = "m1", pressure = 100 }]
[optimize]
[collide]
[mold]
[export]
)";

struct Edit {
  std::string part, from, to; ///< the base with `from` replaced by `to`
};

/// `line` added at the top of section `section`.
Edit add(std::string part, const std::string& section, const std::string& line)
{
  return {std::move(part), "[" + section + "]\n", "[" + section + "]\n" + line + "\n"};
}

std::vector<Edit> edits()
{
  return {
      add("design.name", "design", "name = \"other\""),
      {"design.surface", "surface = \"body.stl\"", "surface = \"other.stl\""},
      add("design.units", "design", "units = \"cm\""),
      add("material.preset", "material", "preset = \"dragon-skin-10\""),
      {"material.youngs_modulus", "youngs_modulus = 86400", "youngs_modulus = 90000"},
      {"material.poisson_ratio", "poisson_ratio = 0.47", "poisson_ratio = 0.45"},
      {"material.density", "density = 1070", "density = 1100"},
      add("material.gravity", "material", "gravity = [0, 0, -9]"),
      add("mesh.edge_length", "mesh", "edge_length = 8"),
      add("mesh.radius_edge_ratio", "mesh", "radius_edge_ratio = 2"),
      add("mesh.min_dihedral_deg", "mesh", "min_dihedral_deg = 12"),
      add("mesh.max_tets", "mesh", "max_tets = 100000"),
      add("mesh.repair", "mesh", "repair = true"),
      add("mesh.surface_triangles", "mesh", "surface_triangles = \"split\""),
      add("sim.basis", "sim", "basis = \"fem-p1\""),
      add("sim.mls_radius", "sim", "mls_radius = 2"),
      add("sim.quadrature_points", "sim", "quadrature_points = 4"),
      {"fixed", "max = [0.5, 9, 9]", "max = [1.5, 9, 9]"},
      add("muscle.diameter", "muscle", "diameter = 2.5"),
      add("muscle.max_pressure", "muscle", "max_pressure = 400"),
      {"muscle.min_bend_radius", "min_bend_radius = 6", "min_bend_radius = 5"},
      add("muscle.segments_per_mm", "muscle", "segments_per_mm = 0.4"),
      add("muscle.stiffness", "muscle", "stiffness = [[-500, 73e6], [26, 4.4e6]]"),
      add("muscle.taut", "muscle", "taut = [[-23e3, 900e6], [-986, 833e6]]"),
      add("muscle.rest_strain_slope", "muscle", "rest_strain_slope = -0.5e-6"),
      add("muscle.rest_strain_intercept", "muscle", "rest_strain_intercept = 0.1"),
      add("muscle.smoothing", "muscle", "smoothing = 12"),
      {"fiber", "[30, 1, 0]", "[30, 2, 0]"},
      add("tracking_curve", "[tracking_curve]", "samples = 20"),
      add("target", "[target]", "weight = 2"),
      add("optimize.enabled", "optimize", "enabled = false"),
      add("optimize.strategy", "optimize", "strategy = \"sequential\""),
      add("optimize.method", "optimize", "method = \"bfgs\""),
      add("optimize.max_iterations", "optimize", "max_iterations = 10"),
      add("optimize.route_only_iterations", "optimize", "route_only_iterations = 5"),
      add("optimize.starts", "optimize", "starts = 2"),
      add("optimize.gradient_tolerance", "optimize", "gradient_tolerance = 1e-5"),
      add("optimize.relative_tolerance", "optimize", "relative_tolerance = 1e-2"),
      add("optimize.decrease_tolerance", "optimize", "decrease_tolerance = 1e-3"),
      add("optimize.weight_curvature", "optimize", "weight_curvature = 1e-3"),
      add("optimize.weight_skin_barrier", "optimize", "weight_skin_barrier = 2"),
      add("optimize.weight_bend_barrier", "optimize", "weight_bend_barrier = 2"),
      add("optimize.weight_pressure_barrier", "optimize", "weight_pressure_barrier = 2"),
      add("optimize.refine", "optimize", "refine = true"),
      add("collide.clearance", "collide", "clearance = 1.5"),
      add("collide.smoothness", "collide", "smoothness = 12"),
      add("collide.samples_per_mm", "collide", "samples_per_mm = 5"),
      add("collide.reoptimize", "collide", "reoptimize = true"),
      add("mold.wall", "mold", "wall = 5"),
      add("mold.voxel", "mold", "voxel = 0.3"),
      add("mold.pull", "mold", "pull = [0, 1, 0]"),
      add("mold.parting", "mold", "parting = { point = [0, 0, 0], normal = [0, 0, 1] }"),
      add("mold.keys", "mold", "keys = 3"),
      add("mold.key_shape", "mold", "key_shape = \"hemisphere\""),
      add("mold.key_diameter", "mold", "key_diameter = 5"),
      add("mold.key_clearance", "mold", "key_clearance = 0.3"),
      add("mold.sprue_diameter", "mold", "sprue_diameter = 5"),
      add("mold.vents", "mold", "vents = 3"),
      add("mold.vent_diameter", "mold", "vent_diameter = 2"),
      add("mold.groove_clearance", "mold", "groove_clearance = 0.4"),
      add("mold.min_silicone", "mold", "min_silicone = 0.6"),
      add("mold.end_channel_length", "mold", "end_channel_length = 6"),
      add("mold.end_channel_diameter", "mold", "end_channel_diameter = 5"),
      add("mold.screw_holes", "mold", "screw_holes = 2"),
      add("mold.screw_diameter", "mold", "screw_diameter = 4"),
      add("mold.draft_deg", "mold", "draft_deg = 2"),
      add("mold.shrink", "mold", "shrink = 0.01"),
      add("mold.labels", "mold", "labels = false"),
      add("export.formats", "export", "formats = [\"stl\", \"3mf\"]"),
      add("export.printer_volume", "export", "printer_volume = [200, 200, 200]"),
      add("export.min_wall", "export", "min_wall = 0.8"),
  };
}

class DesignViewTest : public ::testing::Test {
protected:
  void SetUp() override
  {
    test::write_text(dir_ / "body.stl", "solid x\nendsolid x\n");
    test::write_text(dir_ / "other.stl", "solid x\nendsolid x\n");
  }
  Design parse(const std::string& text) { return parse_design(text, dir_ / "design.toml"); }

  test::TempDir dir_;
};

/// Per part, the base edited at its key: the members the design file's reader sets for that key (the
/// members that change) are copied by that part's row of the view's table and by no other row. A row
/// that copies the wrong member, or a member besides its own, fails here.
TEST_F(DesignViewTest, EachRowCopiesTheMembersItsKeySetsAndNoOtherRowDoes)
{
  const Design base = parse(kBase);
  const Members base_members = members(base);
  const std::vector<std::string> parts = design_view_parts();
  std::set<std::string> edited;
  for (const Edit& edit : edits()) {
    std::string text = kBase;
    const auto at = text.find(edit.from);
    ASSERT_NE(at, std::string::npos) << edit.part << ": " << edit.from;
    text.replace(at, edit.from.size(), edit.to);
    const Design d = parse(text);
    const std::set<std::string> changed = differing(members(d), base_members);
    ASSERT_FALSE(changed.empty()) << edit.part << ": the edit sets no member";
    for (const std::string& part : parts) {
      const std::set<std::string> copied =
          differing(members(design_view(d, {part})), members(design_view(base, {part})));
      if (part == edit.part)
        EXPECT_EQ(copied, changed) << part << "'s row copies " << listed(copied) << "; its key sets "
                                   << listed(changed);
      else
        EXPECT_TRUE(copied.empty()) << part << "'s row copies " << listed(copied) << ", which " << edit.part << " sets";
    }
    edited.insert(edit.part);
  }
  // Every part is edited but material.model, whose one value is "neo-hookean".
  edited.insert("material.model");
  EXPECT_EQ(edited, std::set<std::string>(parts.begin(), parts.end()));
}

/// The design file's reader records every key it reads (Design::values, defaults included): each is
/// a row of the view's table, and each row a key it reads, on the base design and every example. A
/// key added to the reader without a row (its stages would see the default, never "undeclared"), or a
/// row left behind by a key taken out, fails here.
TEST_F(DesignViewTest, TheViewsRowsAreTheKeysTheReaderReads)
{
  const std::vector<std::string> parts = design_view_parts();
  std::vector<Design> designs{parse(kBase)};
  for (const auto& example : fs::directory_iterator(fs::path(FIBERMOLD_SOURCE_DIR) / "examples"))
    if (fs::exists(example.path() / "design.toml")) designs.push_back(load_design(example.path() / "design.toml"));
  std::set<std::string> read;
  for (const Design& d : designs)
    for (const auto& [key, value] : d.values) {
      const auto row = std::find_if(parts.begin(), parts.end(),
                                    [&](const std::string& part) { return design_key_matches(key, part); });
      EXPECT_NE(row, parts.end()) << d.file << ": the reader reads " << key << ", which no row of the view copies";
      if (row != parts.end()) read.insert(*row);
    }
  for (const std::string& part : parts) EXPECT_TRUE(read.contains(part)) << part << ": a row for a key nobody reads";
}

/// What a view holds of a key its stage did not declare, member by member: NaN, kUndeclaredInt or
/// "<undeclared key>", never the default; only the bools keep theirs.
TEST_F(DesignViewTest, AViewWithNothingDeclaredHoldsAnUndeclaredValueInEveryMember)
{
  const Design d = load_design(fs::path(FIBERMOLD_SOURCE_DIR) / "examples/walking-robot/design.toml");
  const std::set<std::string> bools{"mesh.repair", "optimize.enabled", "optimize.refine", "collide.reoptimize",
                                    "mold.labels"};
  for (const auto& [member, value] : members(design_view(d, {}))) {
    const bool undeclared = value.find("nan") != std::string::npos || value.find("<undeclared ") != std::string::npos ||
                            value.find(std::to_string(kUndeclaredInt)) != std::string::npos;
    EXPECT_TRUE(undeclared || bools.contains(member)) << member << " = " << value;
  }
}

TEST_F(DesignViewTest, UndeclaredValuesAreNaNOutOfRangeOrNamed)
{
  const Design d = load_design(fs::path(FIBERMOLD_SOURCE_DIR) / "examples/walking-robot/design.toml");
  ASSERT_EQ(d.fibers.size(), 5u);
  const Design v = design_view(d, {"muscle.diameter"});
  EXPECT_EQ(v.muscle.model.diameter, d.muscle.model.diameter);
  EXPECT_TRUE(std::isnan(v.muscle.max_pressure));
  EXPECT_TRUE(std::isnan(v.mold.block.wall));
  EXPECT_TRUE(v.mold.pull.array().isNaN().all());
  ASSERT_TRUE(v.mold.parting.has_value()); // "auto" would pass for a setting
  EXPECT_TRUE(v.mold.parting->normal.array().isNaN().all());
  ASSERT_TRUE(v.mesh.edge_length.has_value());
  EXPECT_TRUE(std::isnan(*v.mesh.edge_length));
  EXPECT_EQ(v.mold.block.keys, kUndeclaredInt);
  EXPECT_EQ(choice_name(v.sim.basis), "?"); // no name: the reports would write "?"
  EXPECT_EQ(v.design.name, "<undeclared design.name>");
  EXPECT_EQ(v.design.surface, fs::path("<undeclared design.surface>"));
  EXPECT_FALSE(fs::exists(v.design.surface));
  EXPECT_EQ(v.export_.formats, std::vector<std::string>{"<undeclared export.formats>"});
  // An array section holds one element, all undeclared: a loop over it meets NaN, not nothing.
  ASSERT_EQ(v.fibers.size(), 1u);
  EXPECT_EQ(v.fibers[0].name, "<undeclared fiber>");
  ASSERT_EQ(v.fibers[0].points.size(), 2u);
  EXPECT_TRUE(v.fibers[0].points[1].array().isNaN().all());
  ASSERT_EQ(v.targets.size(), 1u);
  EXPECT_EQ(v.targets[0].name, "<undeclared target>");
  EXPECT_TRUE(std::isnan(v.targets[0].weight));
  ASSERT_EQ(v.fixed.size(), 1u);
  EXPECT_EQ(v.fixed[0].region.vertices, std::vector<int>{kUndeclaredInt});
  ASSERT_EQ(v.tracking_curves.size(), 1u);
  EXPECT_EQ(v.tracking_curves[0].samples, kUndeclaredInt);
}

} // namespace
} // namespace fibermold

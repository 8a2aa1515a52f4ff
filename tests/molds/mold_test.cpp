// Molds on known geometry (issue: a 100 × 20 × 20 mm box body with one straight fiber): the groove
// body's volume, both shots' parts, their checks, and the parts put back together.
#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "mesh/surface_check.hpp"
#include "molds/groove.hpp"
#include "molds/level_set.hpp"
#include "molds/mesh_boolean.hpp"
#include "molds/mold_block.hpp"
#include "molds/part_checks.hpp"
#include "molds/parting.hpp"
#include "molds/solids.hpp"

namespace fibermold {
namespace {

constexpr double mm = 1e-3;
const Eigen::Vector3d kPrinter(0.25, 0.21, 0.21);

struct BoxBody {
  SurfaceMesh body = box_solid({0, -10 * mm, -10 * mm}, {100 * mm, 10 * mm, 10 * mm});
  std::vector<Eigen::Vector3d> fiber{{0, 0, 0}, {50 * mm, 0, 0}, {100 * mm, 0, 0}};
  double radius = 1.5 * mm + 0.3 * mm; // muscle radius + groove clearance
};

void expect_parts_ok(const Mold& mold)
{
  for (const MoldPart& p : mold.parts) {
    const PartCheck c = check_part(p.mesh, 1 * mm, kPrinter);
    for (const auto& problem : c.problems) ADD_FAILURE() << p.name << " " << problem;
    EXPECT_GE(c.min_thickness, 1 * mm) << p.name;
    EXPECT_TRUE(c.fits) << p.name;
  }
}

// The printer fit foreseen before carving (stages' require_molds_fit_printer) is a lower bound on the
// parts as checked: their bounding box in the design's frame. A 260 × 20 × 20 mm bar pulled along z has
// halves at least 276.8 × 36.8 × 14.0 mm (8.4 mm of rim for the keys, a 4 mm wall); turned 45° about y
// and pulled along (1, 0, 1), the same halves stand 205.6 mm across x and z, and fit a 250 × 210 × 210
// mm printer that the untilted ones do not (a review found the first version measured in the pull's frame).
TEST(Molds, TheLeastHalfIsMeasuredAsThePartsAreChecked)
{
  const SurfaceMesh bar = box_solid({-0.13, -0.01, -0.01}, {0.13, 0.01, 0.01});
  const MoldBlockOptions o;
  const Eigen::Vector3d printer(0.25, 0.21, 0.21);
  const Eigen::Vector3d along_z = least_half_size(bar, Eigen::Vector3d::UnitZ(), o);
  EXPECT_TRUE(along_z.isApprox(Eigen::Vector3d(0.2768, 0.0368, 0.014), 1e-9)) << along_z.transpose();
  EXPECT_FALSE(printer_orientation(along_z, printer));
  SurfaceMesh turned = bar;
  turned.vertices =
      (turned.vertices * Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitY()).toRotationMatrix().transpose()).eval();
  const Eigen::Vector3d tilted = least_half_size(turned, Eigen::Vector3d(1, 0, 1).normalized(), o);
  EXPECT_NEAR(tilted.x(), (0.2768 + 0.014) / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(tilted.y(), 0.0368, 1e-9);
  EXPECT_NEAR(tilted.z(), (0.2768 + 0.014) / std::sqrt(2.0), 1e-9);
  EXPECT_TRUE(printer_orientation(tilted, printer));
}

TEST(Molds, GrooveShotOfABoxWithAStraightFiber)
{
  const BoxBody b;
  const GrooveBody g = groove_body(b.body, {b.fiber}, b.radius, {0, 0, 1}, 0.25 * mm);
  const double expected = signed_volume(b.body) - 100 * mm * (2 * b.radius * 10 * mm + M_PI * b.radius * b.radius / 2);
  std::printf("groove body %.1f mm³ (mesh %.1f), analytic %.1f; %ld faces\n", g.volume / 1e-9,
              signed_volume(g.mesh) / 1e-9, expected / 1e-9, static_cast<long>(g.mesh.num_faces()));
  EXPECT_NEAR(g.volume, expected, 0.01 * expected);
  EXPECT_NEAR(signed_volume(g.mesh), expected, 0.01 * expected);

  // The groove opens upward: the parting must lie below the groove's bottom (z = −1.8 mm).
  const Parting parting = choose_parting(g.mesh, {0, 0, 1});
  std::printf("shot 1 parting at z = %.2f mm, undercut %.3f mm²\n", parting.point.z() / mm,
              parting.undercut_area / 1e-6);
  EXPECT_LT(parting.point.z(), -1.8 * mm);
  EXPECT_LT(parting.undercut_area, 0.5e-6); // facets only: a groove's worth would be 360 mm²
  const Mold mold = make_mold(g.mesh, parting, {}, {}, "shot1");
  ASSERT_EQ(mold.parts.size(), 2u);
  expect_parts_ok(mold);
  EXPECT_EQ(mold.keys.size(), 4u);
  EXPECT_EQ(mold.vents.size(), 2u);
}

TEST(Molds, GrooveRibBelowThePartingPlaneStaysWithTheUpperHalf)
{
  // A round bar whose muscle dips from 2 mm above the axis at its ends to 4 mm below it mid-way
  // (as the optimized tentacle's): the least undercut is at the widest section, above the groove's
  // bottom there. The plane cuts the end off the upper half's rib, which must go back to the upper
  // half (it slides out of its groove with it), not stay a loose piece of the lower one.
  const SurfaceMesh body = cylinder_solid({0, 0, 0}, {100 * mm, 0, 0}, 10 * mm, 48);
  std::vector<Eigen::Vector3d> fiber;
  for (int k = 0; k <= 100; ++k) fiber.emplace_back(k * mm, 0, (2 - 6 * std::sin(M_PI * k / 100)) * mm);
  const double radius = 1.8 * mm;
  const GrooveBody g = groove_body(body, {fiber}, radius, {0, 0, 1}, 0.25 * mm);
  const Parting parting = choose_parting(g.mesh, {0, 0, 1});
  std::printf("round bar: shot 1 parting at z = %.2f mm, groove bottom at %.2f mm\n", parting.point.z() / mm,
              (-4 * mm - radius) / mm);
  ASSERT_GT(parting.point.z(), -4 * mm - radius);
  MoldBlockOptions o;
  o.sprue_diameter = 2 * mm; // the bottom is round
  const Mold mold = make_mold(g.mesh, parting, {}, o, "shot1");
  ASSERT_EQ(mold.parts.size(), 2u);
  expect_parts_ok(mold);
  // The upper half holds the whole rib, down to the groove's bottom.
  const SurfaceMesh& upper = mold.parts[1].mesh;
  EXPECT_LT(upper.vertices.col(2).minCoeff(), -4 * mm - radius + 0.3 * mm);
  // Nothing of the block was dropped with the piece.
  const double block = signed_volume(mold.parts[0].mesh) + signed_volume(upper);
  const Eigen::Vector3d lo = g.mesh.vertices.colwise().minCoeff(), hi = g.mesh.vertices.colwise().maxCoeff();
  std::printf("halves %.1f mm³\n", block / 1e-9);
  EXPECT_GT(block, 0.9 * ((hi - lo).prod() - signed_volume(g.mesh)));
}

/// A half-turn helix about the x axis from x = 0 to 42 mm, as a dense polyline (the walking robot's
/// twist muscles).
std::vector<Eigen::Vector3d> helix(double sign)
{
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i <= 210; ++i) {
    const double t = i / 210.0, a = M_PI * t;
    line.emplace_back(42 * mm * t, sign * 5 * mm * std::cos(a), sign * 4 * mm * std::sin(a));
  }
  return line;
}

TEST(Molds, GroovesOfCrossingFibersMatchTheirDenseSweep)
{
  // A 42 × 20 × 14 mm block with a straight fiber on its axis and two helices about it, crossing it
  // 4 mm above and below, at 0.1 mm voxels. The groove body sweeps simplified polylines (a tenth of
  // a voxel) and meshes adaptively: its volume must match a sweep of the dense polylines, and its
  // mesh must be a valid solid of the same volume.
  const SurfaceMesh block = box_solid({0, -10 * mm, -7 * mm}, {42 * mm, 10 * mm, 7 * mm});
  const std::vector<std::vector<Eigen::Vector3d>> fibers{
      {{0, 0, 0}, {21 * mm, 0, 0}, {42 * mm, 0, 0}}, helix(1), helix(-1)};
  const double r = 1.8 * mm, voxel = 0.1 * mm;
  const GrooveBody g = groove_body(block, fibers, r, {0, 0, 1}, voxel);
  LevelSet dense = LevelSet::from_mesh(block, voxel), grooves(voxel);
  for (const auto& f : fibers) grooves.add_swept_tube(f, r, 20 * mm);
  dense.subtract(grooves);
  std::printf("crossing grooves: %.1f mm³ (mesh %.1f, %ld faces, adaptivity %g); dense sweep %.1f mm³\n",
              g.volume / 1e-9, signed_volume(g.mesh) / 1e-9, static_cast<long>(g.mesh.num_faces()), g.adaptivity,
              dense.volume() / 1e-9);
  EXPECT_NEAR(g.volume, dense.volume(), 1e-3 * dense.volume());
  EXPECT_NEAR(signed_volume(g.mesh), g.volume, 1e-3 * g.volume);
  EXPECT_EQ(g.adaptivity, kGrooveAdaptivity);
  const SurfaceCheck c = check_surface(g.mesh);
  for (const auto& p : c.problems) ADD_FAILURE() << p.message;
}

TEST(Molds, DraftedShotsShareTheirPartingAndShot1FitsShot2)
{
  // A 6° draft on the box: shot 1's plane (below the groove) serves both shots; every part passes its
  // checks, the drafted groove body lies inside the drafted shot 2 cavity, and neither cavity has an
  // undercut (walls leaning 6° the wrong way would count: the undercut measure skips only faces
  // within 5° of pull).
  const BoxBody b;
  const double voxel = 0.25 * mm;
  const Eigen::Vector3d pull(0, 0, 1);
  const Parting parting = choose_parting(groove_body(b.body, {b.fiber}, b.radius, pull, voxel).mesh, pull);
  const Draft draft = draft_for(b.body, pull, parting.point, 6 * M_PI / 180, voxel);
  EXPECT_NEAR(draft.reach, 10 * mm - parting.point.z(), 1e-12);
  const GrooveBody shot1 = groove_body(b.body, {b.fiber}, b.radius, pull, voxel, kGrooveAdaptivity, &draft);
  const GrooveBody shot2 = groove_body(b.body, {}, b.radius, pull, voxel, kGrooveAdaptivity, &draft);
  const double outside = signed_volume(mesh_difference(shot1.mesh, shot2.mesh));
  std::printf("drafted: parting z = %.2f mm, offset at the plane %.2f mm; shot 1 %.1f mm³, shot 2 %.1f mm³, shot 1 "
              "outside shot 2 %.3f mm³\n",
              parting.point.z() / mm, draft.most() / mm, shot1.volume / 1e-9, shot2.volume / 1e-9, outside / 1e-9);
  EXPECT_LT(outside, 1e-3 * shot1.volume);
  EXPECT_GT(shot2.volume, signed_volume(b.body) + 240 * mm * draft.reach * draft.reach * draft.slope / 2);
  for (const auto& [name, cavity] : {std::pair{"shot1", shot1.mesh}, std::pair{"shot2", shot2.mesh}}) {
    EXPECT_LT(undercut_area(cavity, parting.point, pull), 0.5e-6) << name;
    expect_parts_ok(make_mold(cavity, parting, {}, {}, name));
  }
}

TEST(Molds, OvermoldShotPartsPutBackTogetherMakeTheBlockMinusTheCavity)
{
  const BoxBody b;
  const Parting parting = choose_parting(b.body, {0, 0, 1});
  EXPECT_NEAR(parting.point.z(), 0, 1e-9); // a box: no undercut anywhere, the middle is chosen
  MoldBlockOptions o;
  o.keys = 0; // pins and sockets would not cancel exactly (the fit clearance)
  o.vents = 1;
  const Channel end{{1 * mm, 0, 0}, {-1, 0, 0}, 4 * mm};
  const Mold mold = make_mold(b.body, parting, {end}, o, "shot2");
  expect_parts_ok(mold);
  const SurfaceMesh together = mesh_union(mold.parts[0].mesh, mold.parts[1].mesh);
  const Eigen::Vector3d lo = b.body.vertices.colwise().minCoeff(), hi = b.body.vertices.colwise().maxCoeff();
  const Eigen::Vector3d grow(4 * mm, 4 * mm, 4 * mm);
  const double block = (hi - lo + 2 * grow).prod();
  const double holes = signed_volume(b.body);
  const double together_volume = signed_volume(together);
  std::printf(
      "shot 2: lower %.1f + upper %.1f = %.1f mm³; block − cavity %.1f mm³ (sprue, vent and channel %.1f mm³)\n",
      signed_volume(mold.parts[0].mesh) / 1e-9, signed_volume(mold.parts[1].mesh) / 1e-9, together_volume / 1e-9,
      (block - holes) / 1e-9, (block - holes - together_volume) / 1e-9);
  EXPECT_NEAR(signed_volume(mold.parts[0].mesh) + signed_volume(mold.parts[1].mesh), together_volume, 1e-12);
  EXPECT_NEAR(together_volume, block - holes, 0.005 * (block - holes));
}

TEST(Molds, TheSprueIsCountersunkForTheNozzleAndTheVentsAreNot)
{
  // Shot 1 of the box: the sprue from below through the lower half's 4 mm floor, the vent up through
  // the upper half's roof. On the outer face, the sprue's rim is the 45° seat's, 2 + 2 mm across the
  // axis; the vent's is its own 0.75 mm.
  const BoxBody b;
  MoldBlockOptions o;
  o.keys = 0;
  o.vents = 1;
  const Mold mold = make_mold(b.body, choose_parting(b.body, {0, 0, 1}), {}, o, "shot1");
  expect_parts_ok(mold);
  ASSERT_EQ(mold.sprues.size(), 1u);
  ASSERT_EQ(mold.vents.size(), 1u);
  // The widest rim within 6 mm of `axis` (x, y) among the vertices on the face z = `face`.
  const auto rim = [](const SurfaceMesh& part, const Eigen::Vector3d& axis, double face) {
    double widest = 0;
    for (Eigen::Index v = 0; v < part.num_vertices(); ++v) {
      const Eigen::Vector3d p = part.vertices.row(v);
      const double r = (p - axis).head<2>().norm();
      if (std::abs(p.z() - face) < 1e-6 && r < 6 * mm) widest = std::max(widest, r);
    }
    return widest;
  };
  const double sprue = rim(mold.parts[0].mesh, mold.sprues[0], -14 * mm),
               vent = rim(mold.parts[1].mesh, mold.vents[0], 14 * mm);
  std::printf("on the outer faces: the sprue's rim %.2f mm from its axis, the vent's %.2f mm\n", sprue / mm, vent / mm);
  EXPECT_GT(sprue, 4 * mm * std::cos(M_PI / 20) - 1e-6); // the seat's polygon, 20 facets
  EXPECT_LT(sprue, 4 * mm + 1e-6);
  EXPECT_NEAR(vent, 0.75 * mm, 1e-6);
}

TEST(Molds, EndChannelIsASocketThenAHoleForTheTube)
{
  // A channel leaving the box's end face 1 mm in from it, through the 4 mm wall: 4 mm wide for 2 mm
  // beyond the skin (socket 3 mm from its start), then 3 mm wide. What it takes from the mold is
  // the volume of those two prisms (24 and 20 facets).
  const BoxBody b;
  const Parting parting = choose_parting(b.body, {0, 0, 1});
  MoldBlockOptions o;
  o.keys = 0;
  const auto mold_volume = [&](const std::vector<Channel>& channels) {
    const Mold mold = make_mold(b.body, parting, channels, o, "shot2");
    expect_parts_ok(mold);
    return signed_volume(mold.parts[0].mesh) + signed_volume(mold.parts[1].mesh);
  };
  const double plain = mold_volume({});
  const double stepped = mold_volume({{{1 * mm, 0, 0}, {-1, 0, 0}, 4 * mm, 3 * mm, 3 * mm}});
  const auto prism = [](double radius, double length, int n) {
    return n / 2.0 * radius * radius * std::sin(2 * M_PI / n) * length;
  };
  const double expected = prism(2 * mm, 2 * mm, 24) + prism(1.5 * mm, 2 * mm, 20);
  std::printf("end channel takes %.2f mm³ of the mold (expected %.2f)\n", (plain - stepped) / 1e-9, expected / 1e-9);
  EXPECT_NEAR(plain - stepped, expected, 0.002 * expected);
}

TEST(Molds, EndChannelsTooNearEachOtherAreNamedAsLaid)
{
  // Two 4 mm channels leaving the box's end face 4.5 mm above and below the parting plane's height
  // (z = 2.5 and −2 mm), 2.6 mm apart across: both start within their radius + min_wall of the plane
  // and are laid onto it, where they overlap (2.6 − 4 = −1.4 mm of mold between them). Moved 7.3 mm
  // apart across, 3.3 mm of mold is left.
  const BoxBody b;
  const Parting parting = choose_parting(b.body, {0, 0, 1});
  MoldBlockOptions o;
  o.keys = 0;
  const auto channel = [](double y, double z) { return Channel{{1 * mm, y * mm, z * mm}, {-1, 0, 0}, 4 * mm, 3 * mm}; };
  const Mold near = make_mold(b.body, parting, {channel(-1.3, 2.5), channel(1.3, -2)}, o, "shot2");
  ASSERT_EQ(near.close_channels.size(), 1u);
  EXPECT_EQ(near.close_channels[0].a, 0);
  EXPECT_EQ(near.close_channels[0].b, 1);
  EXPECT_NEAR(near.close_channels[0].wall, -1.4 * mm, 1e-6 * mm);
  const Mold apart = make_mold(b.body, parting, {channel(-1.3, 2.5), channel(6, -2)}, o, "shot2");
  EXPECT_TRUE(apart.close_channels.empty());
}

TEST(Molds, SprueFindsTheFlatOfABottomWhoseLowestVerticesAreOnItsRim)
{
  // A 40 × 10 × 10 mm block whose bottom rises 2 mm from x = 0 to x = 40: within the 0.5 mm band
  // of its lowest point lie only the two vertices of the edge x = 0, but the face itself is flat
  // enough there (x ≤ 10 mm) for the sprue's 6 mm circle (4 mm hole + 2 × 1 mm wall). The
  // underside of a tapered tentacle between two rings of vertices is such a face.
  SurfaceMesh body = box_solid({0, -5 * mm, 0}, {40 * mm, 5 * mm, 10 * mm});
  for (Eigen::Index i = 0; i < body.num_vertices(); ++i)
    if (body.vertices(i, 2) == 0 && body.vertices(i, 0) > 0) body.vertices(i, 2) = 2 * mm;
  const Parting parting = choose_parting(body, {0, 0, 1});
  const Mold mold = make_mold(body, parting, {}, {}, "shot2");
  expect_parts_ok(mold);
  ASSERT_EQ(mold.sprues.size(), 1u);
  const Eigen::Vector3d& sprue = mold.sprues.front();
  std::printf("sprue at (%.2f, %.2f, %.2f) mm\n", sprue.x() / mm, sprue.y() / mm, sprue.z() / mm);
  EXPECT_GE(sprue.x(), 3 * mm); // the whole circle on the bottom
  EXPECT_LE(sprue.x(), 10 * mm - 3 * mm);
  EXPECT_LE(std::abs(sprue.y()), 2 * mm);
  EXPECT_NEAR(sprue.z(), sprue.x() * 2 / 40, 1.1 * mm); // on the bottom face (the hole dips 1 mm in)
}

TEST(Molds, ScrewHolesGoThroughBothHalvesInTheRim)
{
  // Four M3 clearance holes (3.4 mm) besides the four corner keys: at the edge midpoints, through
  // the whole block along pull. They take their prisms' volume from the two parts, which still pass
  // every check (no hole reaches the cavity, no wall thinner than 1 mm).
  const BoxBody b;
  const Parting parting = choose_parting(b.body, {0, 0, 1});
  MoldBlockOptions o;
  const Mold plain = make_mold(b.body, parting, {}, o, "shot2");
  o.screw_holes = 4;
  const Mold screwed = make_mold(b.body, parting, {}, o, "shot2");
  expect_parts_ok(screwed);
  ASSERT_EQ(screwed.screws.size(), 4u);
  const auto volume = [](const Mold& m) { return signed_volume(m.parts[0].mesh) + signed_volume(m.parts[1].mesh); };
  const double height = 20 * mm + 2 * 4 * mm, r = 1.7 * mm;
  const double expected = 4 * 12 * r * r * std::sin(2 * M_PI / 24) * height;
  std::printf("4 screw holes take %.1f mm³ (expected %.1f)\n", (volume(plain) - volume(screwed)) / 1e-9,
              expected / 1e-9);
  EXPECT_NEAR(volume(plain) - volume(screwed), expected, 0.002 * expected);
  for (const Eigen::Vector3d& s : screwed.screws) {
    for (const Eigen::Vector3d& k : screwed.keys) EXPECT_GE((s - k).norm(), 3 * mm + 0.2 * mm + r + 1 * mm);
    // In the rim: outside the cavity's footprint by at least the hole's radius and the printer's wall.
    const double outside = std::max({-s.x(), s.x() - 100 * mm, std::abs(s.y()) - 10 * mm});
    EXPECT_GE(outside, r + 1 * mm);
  }
}

/// A tapered prism along x, `length` long, whose cross-section is a regular polygon of `sides`
/// corners on a circle of radius `r0` at x = 0 to `r1` at x = length, with rings of corners at
/// `rings` + 1 equal steps, at angles (k + ½)·360°/sides from +y toward +z (a flat face at the
/// bottom, as examples/common/tube.py makes its arms); with 10 sides, corners lie at y = 0.
SurfaceMesh polygonal_arm(double length, double r0, double r1, int sides, int rings)
{
  SurfaceMesh m;
  const int n = (rings + 1) * sides;
  m.vertices.resize(n + 2, 3);
  m.faces.resize(2 * sides * (rings + 1), 3);
  m.vertices.row(n) << 0, 0, 0;
  m.vertices.row(n + 1) << length, 0, 0;
  for (int i = 0; i <= rings; ++i) {
    const double t = static_cast<double>(i) / rings, r = r0 + t * (r1 - r0);
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * M_PI * (k + 0.5) / sides;
      m.vertices.row(i * sides + k) << t * length, r * std::cos(a), r * std::sin(a);
    }
  }
  int f = 0;
  for (int k = 0; k < sides; ++k) {
    const int k1 = (k + 1) % sides;
    m.faces.row(f++) << n, k1, k; // the end at x = 0 faces −x
    m.faces.row(f++) << n + 1, rings * sides + k, rings * sides + k1;
    for (int i = 0; i < rings; ++i) {
      const int a = i * sides, b = a + sides;
      m.faces.row(f++) << a + k, a + k1, b + k1;
      m.faces.row(f++) << a + k, b + k1, b + k;
    }
  }
  return m;
}

TEST(Molds, APartingPlaneThroughCavityVerticesMovesOffThem)
{
  // A 10-sided arm pulled along +y has corners on its plane of symmetry, where the least undercut
  // puts the parting plane. The plane moves 2 µm off them; through them, the corner keys' unions
  // came out crossing themselves on a 10-sided tentacle.
  const SurfaceMesh body = polygonal_arm(200 * mm, 14 * mm, 3 * mm, 10, 13);
  const Parting parting = choose_parting(body, {0, 1, 0});
  const double off = (body.vertices.col(1).array() - parting.point.y()).abs().minCoeff();
  EXPECT_NEAR(off, 2e-6, 1e-9);
  EXPECT_NEAR(undercut_area(body, parting.point, parting.normal), 0, 1e-12);
  expect_parts_ok(make_mold(body, parting, {}, {}, "shot2"));
}

TEST(Molds, KeysFitTheirSocketsWithTheClearance)
{
  const BoxBody b;
  const Parting parting = choose_parting(b.body, {0, 0, 1});
  const Mold mold = make_mold(b.body, parting, {}, {}, "shot2");
  expect_parts_ok(mold);
  // Pins and sockets do not collide: the parts, closed, overlap by nothing.
  const SurfaceMesh overlap = mesh_intersection(mold.parts[0].mesh, mold.parts[1].mesh);
  EXPECT_LT(std::abs(signed_volume(overlap)), 1e-12);

  // Eight keys and a fiber-end channel out of the x = 0 face on the parting plane: the key at that
  // face's midpoint would plug the channel and is left out.
  MoldBlockOptions eight;
  eight.keys = 8;
  const Mold with_channel = make_mold(b.body, parting, {{{1 * mm, 0, 0}, {-1, 0, 0}, 4 * mm}}, eight, "shot2");
  EXPECT_EQ(with_channel.keys.size(), 7u);
  for (const Eigen::Vector3d& k : with_channel.keys)
    EXPECT_FALSE(k.x() < 0 && std::abs(k.y()) < 1e-9) << "key on the channel";
  expect_parts_ok(with_channel);
}

TEST(Parting, UprightShareOfTheUpperHalfsContact)
{
  // A 10 mm cube parted at mid-height: above the plane the top (100 mm²) and the sides' upper
  // halves (200 mm²), which lie along the pull.
  const SurfaceMesh cube = box_solid({0, 0, 0}, {10 * mm, 10 * mm, 10 * mm});
  EXPECT_NEAR(upright_share(cube, {0, 0, 5 * mm}, {0, 0, 1}, 3), 2.0 / 3.0, 1e-12);
  // Sides leaning 10° off the pull (a frustum) are not within 3° of it: only the top is above.
  SurfaceMesh frustum = cube;
  for (Eigen::Index i = 0; i < frustum.num_vertices(); ++i)
    if (frustum.vertices(i, 2) > 0)
      frustum.vertices.row(i).head<2>() =
          (frustum.vertices.row(i).head<2>().array() - 5 * mm) * (1 - 2 * std::tan(10 * M_PI / 180)) + 5 * mm;
  EXPECT_NEAR(upright_share(frustum, {0, 0, 5 * mm}, {0, 0, 1}, 3), 0.0, 1e-12);
}

} // namespace
} // namespace fibermold

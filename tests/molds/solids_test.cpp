// The geometry engine on known shapes: primitive solids, exact booleans and cuts (CGAL), level-set
// grooves (OpenVDB) against their analytic volumes.
#include <chrono>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mesh/surface_check.hpp"
#include "molds/level_set.hpp"
#include "molds/mesh_boolean.hpp"
#include "molds/solids.hpp"

namespace fibermold {
namespace {

constexpr double mm = 1e-3;

void expect_valid_solid(const SurfaceMesh& m, const char* what)
{
  const SurfaceCheck c = check_surface(m);
  for (const auto& p : c.problems) ADD_FAILURE() << what << ": " << p.message;
  EXPECT_GT(signed_volume(m), 0) << what;
}

TEST(Solids, VolumesOfPrimitives)
{
  const SurfaceMesh box = box_solid({0, 0, 0}, {0.1, 0.02, 0.03});
  expect_valid_solid(box, "box");
  EXPECT_NEAR(signed_volume(box), 0.1 * 0.02 * 0.03, 1e-15);
  const int n = 64;
  const double polygon = 0.5 * n * std::sin(2 * M_PI / n); // area of the inscribed n-gon / r²
  const SurfaceMesh cyl = cylinder_solid({0, 0, 0}, {0, 0, 0.01}, 0.002, n);
  expect_valid_solid(cyl, "cylinder");
  EXPECT_NEAR(signed_volume(cyl), polygon * 4e-6 * 0.01, 1e-15);
  const SurfaceMesh cone = cone_solid({0, 0, 0}, {0.01, 0, 0}, 0.003, 0.001, n);
  expect_valid_solid(cone, "cone");
  EXPECT_NEAR(signed_volume(cone), polygon * 0.01 / 3 * (9e-6 + 3e-6 + 1e-6), 1e-15);
  const SurfaceMesh half = hemisphere_solid({0, 0, 0}, {0, 1, 0}, 0.003, n);
  expect_valid_solid(half, "hemisphere");
  EXPECT_NEAR(signed_volume(half), 2.0 / 3 * M_PI * 27e-9, 0.01 * 2.0 / 3 * M_PI * 27e-9);
}

TEST(MeshBoolean, DifferenceAndSplitConserveVolume)
{
  const SurfaceMesh block = box_solid({-0.02, -0.02, -0.02}, {0.02, 0.02, 0.02});
  const SurfaceMesh hole = cylinder_solid({0, 0, -0.01}, {0, 0, 0.01}, 0.005, 48);
  const SurfaceMesh carved = mesh_difference(block, hole);
  expect_valid_solid(carved, "carved");
  EXPECT_NEAR(signed_volume(carved), signed_volume(block) - signed_volume(hole), 1e-12);
  const auto [below, above] = split_by_plane(carved, {0, 0, 0.003}, {0, 0, 1});
  expect_valid_solid(below, "below");
  expect_valid_solid(above, "above");
  EXPECT_NEAR(signed_volume(below) + signed_volume(above), signed_volume(carved), 1e-12);
  EXPECT_LT(below.vertices.col(2).maxCoeff(), 0.003 + 1e-12);
  EXPECT_GT(above.vertices.col(2).minCoeff(), 0.003 - 1e-12);
  EXPECT_EQ(count_shells(carved), 2); // the box and the closed hole inside it
  EXPECT_EQ(count_shells(below), 1);
  EXPECT_EQ(count_shells(mesh_union(box_solid({0, 0, 0}, {1, 1, 1}), box_solid({2, 0, 0}, {3, 1, 1}))), 2);
}

/// `m` with its vertices and faces listed in another order, and each face starting at another corner.
SurfaceMesh shuffled(const SurfaceMesh& m)
{
  const Eigen::Index nv = m.num_vertices(), nf = m.num_faces();
  std::vector<int> to(static_cast<std::size_t>(nv));
  for (Eigen::Index v = 0; v < nv; ++v)
    to[static_cast<std::size_t>(v)] = static_cast<int>((2 * nv - 1 - v + nv / 3) % nv);
  SurfaceMesh out;
  out.vertices.resize(nv, 3);
  for (Eigen::Index v = 0; v < nv; ++v) out.vertices.row(to[static_cast<std::size_t>(v)]) = m.vertices.row(v);
  out.faces.resize(nf, 3);
  for (Eigen::Index f = 0; f < nf; ++f) {
    const Eigen::Index g = nf - 1 - f;
    const int r = static_cast<int>(f % 3);
    for (int c = 0; c < 3; ++c) out.faces(g, c) = to[static_cast<std::size_t>(m.faces(f, (c + r) % 3))];
  }
  return out;
}

TEST(MeshBoolean, TheResultIsTheSameByteForByteWhateverOrderTheInputsTrianglesCameIn)
{
  // CGAL's order of the result changed from run to run with threads (the walking robot's shot-2
  // parts): results are put in a canonical order, so the same triangles give the same parts.
  const SurfaceMesh block = box_solid({-0.02, -0.02, -0.02}, {0.02, 0.02, 0.02});
  const SurfaceMesh hole = cylinder_solid({0.003, 0, -0.03}, {0.003, 0, 0.01}, 0.005, 48);
  ASSERT_NE(shuffled(hole).faces, hole.faces);
  const SurfaceMesh a = mesh_difference(block, hole), b = mesh_difference(shuffled(block), shuffled(hole));
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_NEAR(signed_volume(a), signed_volume(block) - signed_volume(mesh_intersection(block, hole)), 1e-12);
}

TEST(MeshBoolean, UnionOfSolidsSharingOnlyAnEdgeNudgesTheSecond)
{
  // A rib's loose end below the parting plane can touch the upper half along an edge only (a
  // coarse tentacle's shot 1): the exact union is not manifold there.
  const SurfaceMesh upper = box_solid({0, 0, 0}, {10 * mm, 10 * mm, 10 * mm});
  const SurfaceMesh rib_end = box_solid({10 * mm, 0, -2 * mm}, {14 * mm, 10 * mm, 0});
  EXPECT_THROW(mesh_union(upper, rib_end), std::runtime_error);
  const SurfaceMesh joined = mesh_union_touching(upper, rib_end, {0, 0, 10e-6});
  expect_valid_solid(joined, "joined");
  EXPECT_EQ(count_shells(joined), 1);
  EXPECT_NEAR(signed_volume(joined), signed_volume(upper) + signed_volume(rib_end), 1e-12);
  // Solids that meet over a face are joined exactly, without the nudge.
  const SurfaceMesh under = box_solid({2 * mm, 2 * mm, -2 * mm}, {8 * mm, 8 * mm, 0});
  const SurfaceMesh exact = mesh_union_touching(upper, under, {0, 0, 10e-6});
  EXPECT_NEAR(exact.vertices.col(2).minCoeff(), -2 * mm, 1e-15);
}

TEST(MeshBoolean, DegenerateFacesAreRemovedAndTheSolidStaysClosed)
{
  // A box whose edge AB gets its midpoint M in one of its two faces: A-M-C and M-B-C replace A-B-C,
  // and the face A-B-M, its corners on one line, closes the surface (as a rotation can round a
  // corefinement's sliver).
  SurfaceMesh m = box_solid({0, 0, 0}, {0.02, 0.01, 0.01});
  const int f = 0, a = m.faces(f, 0), b = m.faces(f, 1), c = m.faces(f, 2);
  const Eigen::Index mid = m.num_vertices();
  m.vertices.conservativeResize(mid + 1, 3);
  m.vertices.row(mid) = (m.vertices.row(a) + m.vertices.row(b)) / 2;
  m.faces.row(f) << a, static_cast<int>(mid), c;
  m.faces.conservativeResize(m.num_faces() + 2, 3);
  m.faces.row(m.num_faces() - 2) << static_cast<int>(mid), b, c;
  m.faces.row(m.num_faces() - 1) << a, b, static_cast<int>(mid);
  const SurfaceCheck before = check_surface(m);
  ASSERT_EQ(before.problems.size(), 1u);
  EXPECT_EQ(before.problems.front().message, "has 1 degenerate (zero-area) faces");

  const SurfaceMesh cleaned = without_degenerate_faces(m);
  expect_valid_solid(cleaned, "cleaned");
  EXPECT_NEAR(signed_volume(cleaned), 0.02 * 0.01 * 0.01, 1e-18);
  EXPECT_EQ(count_shells(cleaned), 1);
}

TEST(LevelSet, GrooveVolumeMatchesTheAnalyticValue)
{
  // A 100 × 20 × 20 mm box, a straight fiber along its axis, a groove of radius 1.8 mm swept to +z:
  // inside the box, cross-section 2 r h + π r²/2 with h = 10 mm.
  const double r = 1.8 * mm, h = 10 * mm, L = 100 * mm, voxel = 0.2 * mm;
  LevelSet body = LevelSet::from_mesh(box_solid({0, -10 * mm, -10 * mm}, {L, 10 * mm, 10 * mm}), voxel);
  EXPECT_NEAR(body.volume(), L * 400e-6, 0.002 * L * 400e-6);
  LevelSet groove(voxel);
  groove.add_swept_tube({{0, 0, 0}, {L / 2, 0, 0}, {L, 0, 0}}, r, h + 2 * r);
  body.subtract(groove);
  const double expected = L * 400e-6 - L * (2 * r * h + M_PI * r * r / 2);
  std::printf("groove body: %.1f mm³ (analytic %.1f)\n", body.volume() / 1e-9, expected / 1e-9);
  EXPECT_NEAR(body.volume(), expected, 0.01 * expected);
  auto t0 = std::chrono::steady_clock::now();
  const SurfaceMesh m = body.mesh(0.0);
  std::printf("mesh %.2f s, %ld faces\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
              (long)m.num_faces());
  expect_valid_solid(m, "groove body mesh");
  EXPECT_NEAR(signed_volume(m), expected, 0.01 * expected);
}

TEST(LevelSet, GrooveSweptAlongATiltedPullMatchesTheAnalyticValue)
{
  // The same box and fiber, pulled 30° off z towards +y: the grid is aligned with pull. Inside the
  // box the groove is a half disc plus a strip 2 r wide along pull up to the top face, whose centre
  // line is h / cos 30° long.
  const double r = 1.8 * mm, h = 10 * mm, L = 60 * mm, voxel = 0.2 * mm, tilt = M_PI / 6;
  const Eigen::Vector3d pull(0, std::sin(tilt), std::cos(tilt));
  LevelSet body = LevelSet::from_mesh(box_solid({0, -10 * mm, -10 * mm}, {L, 10 * mm, 10 * mm}), voxel, pull);
  EXPECT_NEAR(body.volume(), L * 400e-6, 0.002 * L * 400e-6);
  LevelSet groove(voxel, pull);
  groove.add_swept_tube({{-mm, 0, 0}, {L / 2, 0, 0}, {L + mm, 0, 0}}, r, 2 * h);
  body.subtract(groove);
  const double expected = L * 400e-6 - L * (2 * r * h / std::cos(tilt) + M_PI * r * r / 2);
  const SurfaceMesh m = body.mesh(0.0);
  expect_valid_solid(m, "tilted groove body mesh");
  EXPECT_NEAR(body.volume(), expected, 0.005 * expected);
  EXPECT_NEAR(signed_volume(m), expected, 0.005 * expected);
  // The groove's bottom is round about the fiber, whatever the grid's orientation.
  EXPECT_NEAR((m.vertices.rowwise() - Eigen::RowVector3d(L / 2, 0, 0)).rowwise().norm().minCoeff(), r, voxel / 4);
}

TEST(LevelSet, SlopedPieceMatchesSteinersFormula)
{
  // One straight piece rising 4 mm over 40 mm, swept 20 mm up: a parallelogram K (area A, perimeter
  // P) grown by a ball of radius r, whose volume is A · 2r + P · π r² / 2 + 4/3 π r³ (Steiner).
  const double r = 1.8 * mm, L = 20 * mm, voxel = 0.1 * mm;
  const Eigen::Vector3d a(0, 0, -2 * mm), b(40 * mm, 3 * mm, 2 * mm);
  LevelSet piece(voxel);
  piece.add_swept_tube({a, b}, r, L);
  const double area = (b - a).head<2>().norm() * L, perimeter = 2 * ((b - a).norm() + L);
  const double expected = area * 2 * r + perimeter * M_PI * r * r / 2 + 4.0 / 3 * M_PI * r * r * r;
  EXPECT_NEAR(piece.volume(), expected, 0.002 * expected);
}

TEST(LevelSet, DraftedBoxLeansItsWallsByTheAngle)
{
  // A 100 × 20 × 20 mm box grown by r(z) = (10 mm − |z|) tan 3° (parting plane z = 0): every
  // section is its rectangle grown by a disc of r(z), of area A + P r + π r², so the volume is
  // ∫ A + P r + π r² dz, and the walls lean out by 3° toward the plane.
  const double voxel = 0.2 * mm, t = std::tan(3 * M_PI / 180), reach = 10 * mm;
  LevelSet box = LevelSet::from_mesh(box_solid({0, -10 * mm, -10 * mm}, {100 * mm, 10 * mm, 10 * mm}), voxel);
  box.grow([&](double z) { return std::max(0.0, reach - std::abs(z)) * t; }, reach * t);
  const double A = 100 * mm * 20 * mm, P = 240 * mm;
  const double expected = 2 * reach * A + P * reach * reach * t + M_PI * 2 * reach * reach * reach * t * t / 3;
  const SurfaceMesh m = box.mesh(0);
  expect_valid_solid(m, "drafted box");
  std::printf("drafted box: %.1f mm³ (mesh %.1f), analytic %.1f (undrafted %.1f)\n", box.volume() / 1e-9,
              signed_volume(m) / 1e-9, expected / 1e-9, 2 * reach * A / 1e-9);
  EXPECT_NEAR(box.volume(), expected, 0.002 * expected);
  EXPECT_NEAR(signed_volume(m), expected, 0.002 * expected);
  // The end wall x = 100 mm, measured along y = 0: 100 mm + r(z).
  for (const double z : {-8.0, -4.0, 0.0, 4.0, 8.0}) {
    double x = 0;
    for (Eigen::Index i = 0; i < m.num_vertices(); ++i)
      if (std::abs(m.vertices(i, 1)) < 2 * mm && std::abs(m.vertices(i, 2) - z * mm) < voxel)
        x = std::max(x, m.vertices(i, 0));
    EXPECT_NEAR(x, 100 * mm + (reach - std::abs(z * mm)) * t, voxel / 4) << "z = " << z << " mm";
  }
}

TEST(LevelSet, TaperedGrooveWidensUpwardByTheDraft)
{
  // A groove of radius 1.8 mm in the 100 × 20 × 20 mm box, widening by tan 3° per mm above the fiber:
  // its cross-section in the box is a half disc and a trapezoid, π r²/2 + 2 r h + h² tan 3°.
  const double r = 1.8 * mm, h = 10 * mm, L = 100 * mm, voxel = 0.2 * mm, t = std::tan(3 * M_PI / 180);
  LevelSet body = LevelSet::from_mesh(box_solid({0, -10 * mm, -10 * mm}, {L, 10 * mm, 10 * mm}), voxel);
  LevelSet groove(voxel);
  groove.add_swept_tube({{-mm, 0, 0}, {L / 2, 0, 0}, {L + mm, 0, 0}}, r, h + 2 * r, t);
  body.subtract(groove);
  const double expected = L * 400e-6 - L * (2 * r * h + h * h * t + M_PI * r * r / 2);
  const SurfaceMesh m = body.mesh(0);
  expect_valid_solid(m, "tapered groove body");
  std::printf("tapered groove body: %.1f mm³, analytic %.1f (untapered %.1f)\n", body.volume() / 1e-9, expected / 1e-9,
              (expected + L * h * h * t) / 1e-9);
  EXPECT_NEAR(body.volume(), expected, 0.003 * expected);
  // The groove's half-width at the top face is r + h tan 3°; at the fiber it is r.
  double top = HUGE_VAL, bottom = HUGE_VAL;
  for (Eigen::Index i = 0; i < m.num_vertices(); ++i) {
    const Eigen::Vector3d p = m.vertices.row(i);
    if (p.x() < 20 * mm || p.x() > 80 * mm || p.y() < 0) continue;
    if (std::abs(p.z() - (h - voxel)) < voxel / 2) top = std::min(top, p.y());
    if (std::abs(p.z()) < voxel / 2) bottom = std::min(bottom, p.y());
  }
  EXPECT_NEAR(top, r + (h - voxel) * t, voxel / 4);
  EXPECT_NEAR(bottom, r, voxel / 4);
}

TEST(LevelSet, GroovesTouchingOnAGridPlaneMeshAsOneManifoldCavity)
{
  // Two parallel grooves of radius 1.8 mm whose walls meet exactly on the plane y = 0, a grid plane at
  // voxel 0.2 mm: the level set is exactly zero there. The grooves must merge into one cavity with a
  // manifold mesh, not leave a wall of zero thickness. (bench/molds_bench's walking robot, whose
  // grooves leave sub-voxel walls, is where exact zeros once pinched the mesh.)
  const double r = 1.8 * mm, h = 10 * mm, L = 40 * mm, voxel = 0.2 * mm;
  LevelSet body = LevelSet::from_mesh(box_solid({0, -10 * mm, -10 * mm}, {L, 10 * mm, 10 * mm}), voxel);
  LevelSet grooves(voxel);
  for (double y : {-r, r}) grooves.add_swept_tube({{-mm, y, 0}, {L + mm, y, 0}}, r, h + 2 * r);
  body.subtract(grooves);
  const SurfaceMesh m = body.mesh(0.0);
  expect_valid_solid(m, "grooves touching");
  // Cross-section removed: a 4 r × h rectangle above the fibers and two half discs below.
  const double expected = L * 400e-6 - L * (4 * r * h + M_PI * r * r);
  EXPECT_NEAR(signed_volume(m), expected, 0.005 * expected);
}

} // namespace
} // namespace fibermold

#include "mesh/tetrahedralize.hpp"

#include <algorithm>
#include <array>
#include <set>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mesh/mesh_quality.hpp"
#include "mesh/surface_check.hpp"
#include "primitives.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

struct Case {
  const char* name;
  SurfaceMesh surface;
  double edge;
};

std::vector<Case> primitives()
{
  return {{"box", test::box({0, 0, 0}, {0.03, 0.02, 0.01}, 4), 0.004},
          {"cylinder", test::cylinder(0.008, 0.04, 20, 8), 0.004},
          {"sphere", test::sphere(0.015, 24, 12), 0.005},
          {"torus", test::torus(0.03, 0.01, 32, 12), 0.005}};
}

/// Faces as rotation-normalised triples (keeps orientation, forgets the starting corner).
std::set<std::array<int, 3>> oriented_faces(const Eigen::MatrixX3i& faces, const Eigen::VectorXi& map)
{
  std::set<std::array<int, 3>> out;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    std::array<int, 3> t{map.size() ? map(faces(f, 0)) : faces(f, 0), map.size() ? map(faces(f, 1)) : faces(f, 1),
                         map.size() ? map(faces(f, 2)) : faces(f, 2)};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.insert(t);
  }
  return out;
}

class Tetrahedralize : public ::testing::TestWithParam<int> {};

TEST_P(Tetrahedralize, KeepsVolumeOrientationAndTheSurfaceExactly)
{
  const Case c = primitives()[GetParam()];
  SCOPED_TRACE(c.name);
  ASSERT_TRUE(check_surface(c.surface).ok());
  NullProgress progress;
  const TetMesh mesh = tetrahedralize(c.surface, {c.edge, 1.5, 10, false}, progress);
  ASSERT_EQ(mesh.nodes_per_tet(), 4);
  ASSERT_GT(mesh.num_tets(), 50);

  const double surface_volume = signed_volume(c.surface);
  EXPECT_NEAR(mesh.volume(), surface_volume, 1e-9 * surface_volume);
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) ASSERT_GT(mesh.tet_volume(t), 0) << "tet " << t;

  ASSERT_EQ(mesh.surface_to_node.size(), c.surface.num_vertices());
  for (Eigen::Index v = 0; v < c.surface.num_vertices(); ++v)
    ASSERT_EQ(mesh.nodes.row(mesh.surface_to_node(v)), c.surface.vertices.row(v)) << "vertex " << v;
  EXPECT_EQ(oriented_faces(mesh.boundary_faces, {}), oriented_faces(c.surface.faces, mesh.surface_to_node));

  const MeshQuality q = mesh_quality(mesh);
  EXPECT_EQ(q.inverted_tets, 0);
  EXPECT_GT(q.min_dihedral_deg, 1.0); // slivers at the skin are bounded by the input faces (-Y)
  EXPECT_LT(q.mean_edge_length, 1.5 * c.edge);
}

INSTANTIATE_TEST_SUITE_P(Primitives, Tetrahedralize, ::testing::Range(0, 4));

TEST(Tetrahedralize, CavitiesStayEmpty)
{
  SurfaceMesh inner = test::sphere(0.008);
  inner.faces.col(1).swap(inner.faces.col(2));
  const SurfaceMesh hollow = test::combine(test::sphere(0.02), inner);
  NullProgress progress;
  const TetMesh mesh = tetrahedralize(hollow, {0.004, 1.5, 10, false}, progress);
  EXPECT_NEAR(mesh.volume(), signed_volume(hollow), 1e-9 * signed_volume(hollow));
  EXPECT_EQ(oriented_faces(mesh.boundary_faces, {}), oriented_faces(hollow.faces, mesh.surface_to_node));
}

TEST(Tetrahedralize, WorksAtAnyScale)
{
  // A 20 µm sphere and a 20 m one: the volume bound must neither underflow nor overflow.
  NullProgress progress;
  for (double radius : {1e-5, 10.0}) {
    const SurfaceMesh s = test::sphere(radius, 16, 8);
    const TetMesh mesh = tetrahedralize(s, {radius / 3, 1.5, 10, false}, progress);
    EXPECT_NEAR(mesh.volume(), signed_volume(s), 1e-9 * signed_volume(s)) << radius;
    EXPECT_LT(mesh.num_tets(), 5000) << radius;
  }
}

TEST(TetrahedralizeQuadratic, TenNodeTetsHaveEdgeMidpointsInVtkOrder)
{
  NullProgress progress;
  const TetMesh mesh = tetrahedralize(test::sphere(0.015), {0.006, 1.5, 10, true}, progress);
  ASSERT_EQ(mesh.nodes_per_tet(), 10);
  constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (int e = 0; e < 6; ++e) {
      const Eigen::RowVector3d mid =
          (mesh.nodes.row(mesh.tets(t, kEdges[e][0])) + mesh.nodes.row(mesh.tets(t, kEdges[e][1]))) / 2;
      ASSERT_LT((mesh.nodes.row(mesh.tets(t, 4 + e)) - mid).norm(), 1e-12) << "tet " << t << " edge " << e;
    }
  EXPECT_NEAR(mesh.volume(), signed_volume(test::sphere(0.015)), 1e-9 * mesh.volume());
}

TEST(TetMeshFile, RoundTripsAndRejectsDamage)
{
  NullProgress progress;
  const TetMesh mesh = tetrahedralize(test::cylinder(0.01, 0.03), {0.005, 1.5, 10, false}, progress);
  test::TempDir dir;
  save_tet_mesh(mesh, dir / "body.tetmesh");
  const TetMesh back = load_tet_mesh(dir / "body.tetmesh");
  EXPECT_EQ(back.nodes, mesh.nodes);
  EXPECT_EQ(back.tets, mesh.tets);
  EXPECT_EQ(back.boundary_faces, mesh.boundary_faces);
  EXPECT_EQ(back.surface_to_node, mesh.surface_to_node);
  EXPECT_EQ(back.surface_faces, mesh.surface_faces);
  EXPECT_EQ(back.surface_vertices, mesh.surface_vertices);
  EXPECT_EQ(back.place_face, mesh.place_face);
  EXPECT_EQ(back.place_weights, mesh.place_weights);
  EXPECT_EQ(mesh.place_face.size(), mesh.nodes.rows());

  std::string bytes = test::read_text(dir / "body.tetmesh");
  test::write_text(dir / "truncated.tetmesh", bytes.substr(0, bytes.size() / 2));
  EXPECT_THROW(load_tet_mesh(dir / "truncated.tetmesh"), std::runtime_error);
  bytes[bytes.size() / 2] ^= 1;
  test::write_text(dir / "flipped.tetmesh", bytes);
  EXPECT_THROW(load_tet_mesh(dir / "flipped.tetmesh"), std::runtime_error);
}

TEST(MeshQuality, RegularTetFigures)
{
  const Eigen::Vector3d a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);
  EXPECT_NEAR(radius_edge_ratio(a, b, c, d), std::sqrt(6.0) / 4, 1e-12);
  TetMesh m;
  m.nodes.resize(4, 3);
  m.nodes << a.transpose(), b.transpose(), c.transpose(), d.transpose();
  m.tets.resize(1, 4);
  m.tets << 0, 2, 1, 3;
  if (m.tet_volume(0) < 0) std::swap(m.tets(0, 0), m.tets(0, 1));
  const MeshQuality q = mesh_quality(m);
  EXPECT_NEAR(q.min_dihedral_deg, std::acos(1.0 / 3) * 180 / M_PI, 1e-9);
  EXPECT_NEAR(q.max_dihedral_deg, q.min_dihedral_deg, 1e-9);
  EXPECT_NEAR(q.mean_edge_length, std::sqrt(8.0), 1e-12);
  EXPECT_NEAR(q.volume, 8.0 / 3, 1e-12);
}

} // namespace
} // namespace fibermold

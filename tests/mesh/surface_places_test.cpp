// The mesh's surface nodes placed on the input surface: what is given on the input (a deformed
// copy of it, its vertex indices) reaches the nodes whether the triangles were kept, split by
// TetGen or remeshed. An affine deformation of the input must reach every surface node exactly
// (barycentric weights reproduce it), and the vertices of one face of a box select that face's nodes.
#include <gtest/gtest.h>

#include "mesh/body_mesh.hpp"
#include "mesh/surface_places.hpp"
#include "primitives.hpp"

namespace fibermold {
namespace {

Eigen::Vector3d affine(const Eigen::Vector3d& X)
{
  Eigen::Matrix3d A;
  A << 1.1, 0.2, 0, -0.1, 0.9, 0.3, 0.05, 0, 1.2;
  return A * X + Eigen::Vector3d(0.001, -0.002, 0.003);
}

struct Placed {
  SurfaceMesh input;
  TetMesh mesh;
  SurfaceTriangles treatment;
};

Placed placed(const SurfaceMesh& input, SurfaceTriangles policy, double edge)
{
  NullProgress progress;
  BodyMesh body = mesh_body(input, policy, {edge, 1.5, 10, false, true}, progress);
  return {input, std::move(body.mesh), body.surface.treatment};
}

void expect_affine_carried(const Placed& p)
{
  Eigen::MatrixX3d deformed = p.input.vertices;
  for (Eigen::Index v = 0; v < deformed.rows(); ++v)
    deformed.row(v) = affine(p.input.vertices.row(v).transpose()).transpose();
  const auto carried = carried_surface(p.mesh, deformed);
  std::vector<bool> on(static_cast<std::size_t>(p.mesh.nodes.rows()), false);
  for (Eigen::Index i = 0; i < p.mesh.boundary_faces.size(); ++i)
    on[static_cast<std::size_t>(p.mesh.boundary_faces(i))] = true;
  EXPECT_EQ(carried.size(), static_cast<std::size_t>(std::count(on.begin(), on.end(), true)));
  double worst = 0;
  for (const auto& [node, position] : carried) {
    EXPECT_TRUE(on[static_cast<std::size_t>(node)]);
    worst = std::max(worst, (position - affine(p.mesh.nodes.row(node).transpose())).norm());
  }
  EXPECT_LT(worst, 1e-9) << choice_name(p.treatment);
}

/// The input vertices on the face x = 0 select every surface node on it, and no other.
void expect_face_selected(const Placed& p)
{
  std::vector<int> vertices;
  for (Eigen::Index v = 0; v < p.input.num_vertices(); ++v)
    if (p.input.vertices(v, 0) < 1e-12) vertices.push_back(static_cast<int>(v));
  const std::vector<int> nodes = nodes_of_vertices(p.mesh, vertices);
  std::vector<int> expected;
  std::vector<bool> on(static_cast<std::size_t>(p.mesh.nodes.rows()), false);
  for (Eigen::Index i = 0; i < p.mesh.boundary_faces.size(); ++i)
    on[static_cast<std::size_t>(p.mesh.boundary_faces(i))] = true;
  for (Eigen::Index i = 0; i < p.mesh.nodes.rows(); ++i)
    if (on[static_cast<std::size_t>(i)] && p.mesh.nodes(i, 0) < 1e-9) expected.push_back(static_cast<int>(i));
  EXPECT_GT(expected.size(), 3u);
  EXPECT_EQ(nodes, expected) << choice_name(p.treatment);
}

TEST(SurfacePlaces, KeptTrianglesPlaceEachVertexNodeOnItself)
{
  const Placed p =
      placed(test::box({0, 0, 0}, {0.03, 0.01, 0.01}, Eigen::Vector3i(6, 2, 2)), SurfaceTriangles::automatic, 0.005);
  ASSERT_EQ(p.treatment, SurfaceTriangles::keep);
  EXPECT_EQ(p.mesh.surface_vertices.rows(), 0); // the input's vertices are the first nodes
  for (Eigen::Index v = 0; v < p.input.num_vertices(); ++v) {
    ASSERT_EQ(p.mesh.surface_to_node(v), v);
    EXPECT_EQ(p.mesh.place_weights.row(v).maxCoeff(), 1.0);
  }
  expect_affine_carried(p);
  expect_face_selected(p);
}

TEST(SurfacePlaces, SplitTrianglesPlaceTheAddedPointsOnThem)
{
  const Placed p = placed(test::box({0, 0, 0}, {0.03, 0.01, 0.01}, 1), SurfaceTriangles::automatic, 0.003);
  ASSERT_EQ(p.treatment, SurfaceTriangles::split);
  ASSERT_GT(p.mesh.nodes.rows(), 8);
  expect_affine_carried(p);
  expect_face_selected(p);
}

TEST(SurfacePlaces, AutoRemeshesDenseSurfacesSplitsLargeTrianglesAndKeepsTheRest)
{
  const Eigen::Vector3d lo(0, 0, 0), hi(0.03, 0.01, 0.01);
  const auto treatment = [](const SurfaceMesh& s) { return surface_treatment(SurfaceTriangles::automatic, s, 0.004); };
  EXPECT_EQ(treatment(test::box(lo, hi, 1)), SurfaceTriangles::split); // 12 triangles, 30 mm edges
  EXPECT_EQ(treatment(test::box(lo, hi, Eigen::Vector3i(8, 3, 3))), SurfaceTriangles::keep); // 3.3–3.75 mm edges
  SurfaceMesh dense = test::box(lo, hi, Eigen::Vector3i(60, 20, 20));                        // 0.5 mm grid
  EXPECT_EQ(treatment(dense), SurfaceTriangles::remesh);
  // A dense scan with a few long triangles (a corner pulled 20 mm out): remeshed, which splits
  // them too; split, it would keep every one of its vertices.
  dense.vertices(0, 0) = -0.02;
  ASSERT_GT(longest_edge(dense), 2 * 0.004);
  EXPECT_EQ(treatment(dense), SurfaceTriangles::remesh);
}

TEST(SurfacePlaces, ARemeshedDenseSurfaceIsPlacedOnTheInput)
{
  const Placed p =
      placed(test::box({0, 0, 0}, {0.03, 0.01, 0.01}, Eigen::Vector3i(60, 20, 20)), SurfaceTriangles::automatic, 0.004);
  ASSERT_EQ(p.treatment, SurfaceTriangles::remesh);
  EXPECT_LT(p.mesh.nodes.rows(), p.input.num_vertices());
  EXPECT_EQ(p.mesh.surface_vertices, p.input.vertices); // kept for the molds: the body as given
  EXPECT_EQ(p.mesh.surface_faces, p.input.faces);
  expect_affine_carried(p);
  expect_face_selected(p);
  // Each input vertex's node is the surface node nearest it: within an edge length.
  for (Eigen::Index v = 0; v < p.input.num_vertices(); ++v)
    ASSERT_LT((p.mesh.nodes.row(p.mesh.surface_to_node(v)) - p.input.vertices.row(v)).norm(), 0.004) << v;
}

} // namespace
} // namespace fibermold

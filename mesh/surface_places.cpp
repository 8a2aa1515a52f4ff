#include "mesh/surface_places.hpp"

#include <algorithm>
#include <memory>
#include <set>

#include <nanoflann.hpp>

#include "mesh/surface_distance.hpp"

namespace fibermold {

namespace {

/// Barycentric weights of p's projection on triangle (a, b, c), clamped into it.
Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c)
{
  const Eigen::Vector3d e0 = b - a, e1 = c - a, q = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1), d20 = q.dot(e0), d21 = q.dot(e1);
  const double den = d00 * d11 - d01 * d01;
  Eigen::Vector3d w(1, 0, 0);
  if (den > 0) {
    const double v = (d11 * d20 - d01 * d21) / den, u = (d00 * d21 - d01 * d20) / den;
    w = Eigen::Vector3d(1 - v - u, v, u).cwiseMax(0.0);
    w /= w.sum();
  }
  return w;
}

std::vector<bool> surface_nodes(const TetMesh& mesh)
{
  std::vector<bool> on(static_cast<std::size_t>(mesh.nodes.rows()), false);
  for (Eigen::Index i = 0; i < mesh.boundary_faces.size(); ++i)
    on[static_cast<std::size_t>(mesh.boundary_faces(i))] = true;
  return on;
}

} // namespace

void attach_to_surface(TetMesh& mesh, const SurfaceMesh& input)
{
  const Eigen::Index nodes = mesh.nodes.rows(), vertices = input.num_vertices();
  const std::vector<bool> on_surface = surface_nodes(mesh);
  mesh.surface_faces = input.faces;
  mesh.place_face = Eigen::VectorXi::Constant(nodes, -1);
  mesh.place_weights = Eigen::MatrixX3d::Zero(nodes, 3);

  // The input vertices TetGen kept are the first nodes, at the same coordinates.
  std::vector<int> face_at(static_cast<std::size_t>(vertices), -1), corner_at(face_at.size(), -1);
  for (Eigen::Index f = 0; f < input.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = input.faces(f, k);
      if (face_at[static_cast<std::size_t>(v)] < 0) {
        face_at[static_cast<std::size_t>(v)] = static_cast<int>(f);
        corner_at[static_cast<std::size_t>(v)] = k;
      }
    }
  const auto is_vertex = [&](Eigen::Index i) {
    return i < vertices && face_at[static_cast<std::size_t>(i)] >= 0 && mesh.nodes.row(i) == input.vertices.row(i);
  };
  std::unique_ptr<SurfaceDistance> distance;
  for (Eigen::Index i = 0; i < nodes; ++i) {
    if (!on_surface[static_cast<std::size_t>(i)]) continue;
    if (is_vertex(i)) {
      mesh.place_face(i) = face_at[static_cast<std::size_t>(i)];
      mesh.place_weights(i, corner_at[static_cast<std::size_t>(i)]) = 1;
      continue;
    }
    if (!distance) distance = std::make_unique<SurfaceDistance>(input.vertices, input.faces);
    const Eigen::Vector3d X = mesh.nodes.row(i).transpose();
    const SurfaceDistance::Closest c = distance->closest(X);
    const auto corner = [&](int k) { return Eigen::Vector3d(input.vertices.row(input.faces(c.face, k))); };
    mesh.place_face(i) = static_cast<int>(c.face);
    mesh.place_weights.row(i) = barycentric(c.point, corner(0), corner(1), corner(2)).transpose();
  }

  mesh.surface_to_node.resize(vertices);
  bool all_nodes = true;
  for (Eigen::Index v = 0; v < vertices; ++v)
    all_nodes = all_nodes && v < nodes && mesh.nodes.row(v) == input.vertices.row(v);
  if (all_nodes) {
    for (Eigen::Index v = 0; v < vertices; ++v) mesh.surface_to_node(v) = static_cast<int>(v);
    mesh.surface_vertices.resize(0, 3);
    return;
  }
  mesh.surface_vertices = input.vertices; // the body as given, for what is made of its shape (the molds)
  // Remeshed: each input vertex's nearest surface node.
  std::vector<int> surface_index;
  for (Eigen::Index i = 0; i < nodes; ++i)
    if (on_surface[static_cast<std::size_t>(i)]) surface_index.push_back(static_cast<int>(i));
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(surface_index.size()), 3);
  for (std::size_t k = 0; k < surface_index.size(); ++k)
    points.row(static_cast<Eigen::Index>(k)) = mesh.nodes.row(surface_index[k]);
  const nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixX3d> tree(3, std::cref(points), 10);
  for (Eigen::Index v = 0; v < vertices; ++v) {
    const Eigen::Vector3d q = input.vertices.row(v).transpose();
    Eigen::Index found = 0;
    double squared = 0;
    tree.query(q.data(), 1, &found, &squared);
    mesh.surface_to_node(v) = surface_index[static_cast<std::size_t>(found)];
  }
}

std::vector<std::pair<int, Eigen::Vector3d>> carried_surface(const TetMesh& mesh, const Eigen::MatrixX3d& deformed)
{
  std::vector<std::pair<int, Eigen::Vector3d>> out;
  if (mesh.place_face.size() == 0) {
    for (Eigen::Index v = 0; v < mesh.surface_to_node.size(); ++v)
      out.emplace_back(mesh.surface_to_node(v), deformed.row(v).transpose());
    return out;
  }
  for (Eigen::Index i = 0; i < mesh.place_face.size(); ++i) {
    const int f = mesh.place_face(i);
    if (f < 0) continue;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) p += mesh.place_weights(i, k) * deformed.row(mesh.surface_faces(f, k)).transpose();
    out.emplace_back(static_cast<int>(i), p);
  }
  return out;
}

std::vector<int> nodes_of_vertices(const TetMesh& mesh, const std::vector<int>& vertices)
{
  const std::set<int> selected(vertices.begin(), vertices.end());
  std::set<int> nodes;
  for (int v : vertices) nodes.insert(mesh.surface_to_node(v));
  for (Eigen::Index i = 0; i < mesh.place_face.size(); ++i) {
    const int f = mesh.place_face(i);
    if (f < 0) continue;
    bool inside = true; // every corner the place leans on is selected
    for (int k = 0; k < 3; ++k)
      inside = inside && (mesh.place_weights(i, k) <= 1e-9 || selected.count(mesh.surface_faces(f, k)) > 0);
    if (inside) nodes.insert(static_cast<int>(i));
  }
  return {nodes.begin(), nodes.end()};
}

} // namespace fibermold

#include "mesh/surface_mesh.hpp"

#include <algorithm>
#include <numeric>

#include <Eigen/Geometry>

namespace fibermold {

double signed_volume(const SurfaceMesh& surface)
{
  // V = Σ_f  x0 · (x1 × x2) / 6, with coordinates relative to the centroid for accuracy.
  const Eigen::RowVector3d c = surface.vertices.colwise().mean();
  double six_v = 0;
  for (Eigen::Index f = 0; f < surface.num_faces(); ++f) {
    const Eigen::Vector3d a = (surface.vertices.row(surface.faces(f, 0)) - c).transpose();
    const Eigen::Vector3d b = (surface.vertices.row(surface.faces(f, 1)) - c).transpose();
    const Eigen::Vector3d d = (surface.vertices.row(surface.faces(f, 2)) - c).transpose();
    six_v += a.dot(b.cross(d));
  }
  return six_v / 6.0;
}

std::vector<int> face_shells(const SurfaceMesh& s)
{
  // Union-find over the vertices, joined along every face.
  std::vector<int> parent(static_cast<std::size_t>(s.num_vertices()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (Eigen::Index f = 0; f < s.num_faces(); ++f)
    for (int c = 1; c < 3; ++c) parent[find(s.faces(f, c))] = find(s.faces(f, 0));
  std::vector<int> shell_of_root(parent.size(), -1), shells(static_cast<std::size_t>(s.num_faces()));
  int count = 0;
  for (Eigen::Index f = 0; f < s.num_faces(); ++f) {
    int& shell = shell_of_root[find(s.faces(f, 0))];
    if (shell < 0) shell = count++;
    shells[f] = shell;
  }
  return shells;
}

double longest_edge(const SurfaceMesh& s)
{
  double longest = 0;
  for (Eigen::Index f = 0; f < s.num_faces(); ++f)
    for (int c = 0; c < 3; ++c)
      longest = std::max(longest, (s.vertices.row(s.faces(f, c)) - s.vertices.row(s.faces(f, (c + 1) % 3))).norm());
  return longest;
}

double mean_edge_length(const SurfaceMesh& s)
{
  double sum = 0;
  for (Eigen::Index f = 0; f < s.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) sum += (s.vertices.row(s.faces(f, c)) - s.vertices.row(s.faces(f, (c + 1) % 3))).norm();
  return s.num_faces() > 0 ? sum / (3.0 * static_cast<double>(s.num_faces())) : 0.0;
}

double surface_area(const SurfaceMesh& s)
{
  double area = 0;
  for (Eigen::Index f = 0; f < s.num_faces(); ++f) {
    const Eigen::Vector3d a = s.vertices.row(s.faces(f, 0)), b = s.vertices.row(s.faces(f, 1)),
                          c = s.vertices.row(s.faces(f, 2));
    area += (b - a).cross(c - a).norm() / 2;
  }
  return area;
}

} // namespace fibermold

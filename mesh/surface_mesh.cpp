#include "mesh/surface_mesh.hpp"

#include <algorithm>
#include <array>
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

SurfaceMesh canonical_order(const SurfaceMesh& surface)
{
  const Eigen::Index nv = surface.num_vertices(), nf = surface.num_faces();
  std::vector<Eigen::Index> by_position(static_cast<std::size_t>(nv));
  std::iota(by_position.begin(), by_position.end(), Eigen::Index{0});
  const auto at = [&](Eigen::Index v) {
    return std::array<double, 3>{surface.vertices(v, 0), surface.vertices(v, 1), surface.vertices(v, 2)};
  };
  std::stable_sort(by_position.begin(), by_position.end(),
                   [&](Eigen::Index a, Eigen::Index b) { return at(a) < at(b); });
  SurfaceMesh out;
  out.source = surface.source;
  out.vertices.resize(nv, 3);
  std::vector<int> index_of(static_cast<std::size_t>(nv));
  for (Eigen::Index k = 0; k < nv; ++k) {
    out.vertices.row(k) = surface.vertices.row(by_position[static_cast<std::size_t>(k)]);
    index_of[static_cast<std::size_t>(by_position[static_cast<std::size_t>(k)])] = static_cast<int>(k);
  }
  std::vector<std::array<int, 3>> faces(static_cast<std::size_t>(nf));
  for (Eigen::Index f = 0; f < nf; ++f) {
    std::array<int, 3>& t = faces[static_cast<std::size_t>(f)];
    for (int c = 0; c < 3; ++c)
      t[static_cast<std::size_t>(c)] = index_of[static_cast<std::size_t>(surface.faces(f, c))];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end()); // the same turn
  }
  std::sort(faces.begin(), faces.end());
  out.faces.resize(nf, 3);
  for (Eigen::Index f = 0; f < nf; ++f) {
    const std::array<int, 3>& t = faces[static_cast<std::size_t>(f)];
    out.faces.row(f) << t[0], t[1], t[2];
  }
  return out;
}

} // namespace fibermold

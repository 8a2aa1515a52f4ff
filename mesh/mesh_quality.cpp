#include "mesh/mesh_quality.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "core/units.hpp"

namespace fibermold {

namespace {

constexpr std::array<std::array<int, 2>, 6> kEdges{{{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}}};

/// The six dihedral angles (degrees) at the edges of a tet.
std::array<double, 6> dihedral_angles(const std::array<Eigen::Vector3d, 4>& p)
{
  std::array<double, 6> angles{};
  for (int e = 0; e < 6; ++e) {
    const int i = kEdges[e][0], j = kEdges[e][1];
    int k = 0, l = 0;
    for (int m = 0, n = 0; m < 4; ++m)
      if (m != i && m != j) (n++ == 0 ? k : l) = m;
    const Eigen::Vector3d axis = (p[j] - p[i]).normalized();
    Eigen::Vector3d u = p[k] - p[i], v = p[l] - p[i];
    u -= u.dot(axis) * axis;
    v -= v.dot(axis) * axis;
    angles[e] = std::acos(std::clamp(u.normalized().dot(v.normalized()), -1.0, 1.0)) / units::degree;
  }
  return angles;
}

/// Each corner edge once, as (smaller, larger) node index, sorted.
std::vector<std::pair<int, int>> unique_edges(const TetMesh& mesh)
{
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<std::size_t>(6 * mesh.num_tets()));
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (const auto& e : kEdges) {
      const int a = mesh.tets(t, e[0]), b = mesh.tets(t, e[1]);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

} // namespace

double mean_edge_length(const TetMesh& mesh)
{
  const std::vector<std::pair<int, int>> edges = unique_edges(mesh);
  double length = 0;
  for (const auto& [a, b] : edges) length += (mesh.nodes.row(a) - mesh.nodes.row(b)).norm();
  return edges.empty() ? 0 : length / static_cast<double>(edges.size());
}

double radius_edge_ratio(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                         const Eigen::Vector3d& d)
{
  // Circumcentre relative to a: (|u|²(v×w) + |v|²(w×u) + |w|²(u×v)) / (2 u·(v×w)).
  const Eigen::Vector3d u = b - a, v = c - a, w = d - a;
  const double denominator = 2 * u.dot(v.cross(w));
  const Eigen::Vector3d centre =
      (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) / denominator;
  const double shortest = std::min({u.norm(), v.norm(), w.norm(), (c - b).norm(), (d - b).norm(), (d - c).norm()});
  return centre.norm() / shortest;
}

MeshQuality mesh_quality(const TetMesh& mesh, double max_ratio, double min_dihedral_deg)
{
  MeshQuality q;
  q.min_dihedral_deg = 180;
  double ratio_sum = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    std::array<Eigen::Vector3d, 4> p;
    for (int k = 0; k < 4; ++k) p[k] = mesh.nodes.row(mesh.tets(t, k)).transpose();
    const double v = mesh.tet_volume(t);
    q.volume += v;
    if (v <= 0) {
      ++q.inverted_tets;
      continue;
    }
    const std::array<double, 6> angles = dihedral_angles(p);
    const auto [smallest, largest] = std::minmax_element(angles.begin(), angles.end());
    q.min_dihedral_deg = std::min(q.min_dihedral_deg, *smallest);
    q.max_dihedral_deg = std::max(q.max_dihedral_deg, *largest);
    if (*smallest < min_dihedral_deg) ++q.under_dihedral;
    const double ratio = radius_edge_ratio(p[0], p[1], p[2], p[3]);
    ratio_sum += ratio;
    if (ratio > max_ratio) ++q.over_ratio;
    if (ratio > q.max_radius_edge_ratio) q.worst_at = (p[0] + p[1] + p[2] + p[3]) / 4;
    q.max_radius_edge_ratio = std::max(q.max_radius_edge_ratio, ratio);
  }
  const std::vector<std::pair<int, int>> edges = unique_edges(mesh);
  double length = 0;
  q.min_edge_length = edges.empty() ? 0 : HUGE_VAL;
  for (const auto& [a, b] : edges) {
    const double l = (mesh.nodes.row(a) - mesh.nodes.row(b)).norm();
    length += l;
    q.min_edge_length = std::min(q.min_edge_length, l);
    q.max_edge_length = std::max(q.max_edge_length, l);
  }
  q.mean_edge_length = edges.empty() ? 0 : length / static_cast<double>(edges.size());
  const auto good = mesh.num_tets() - q.inverted_tets;
  q.mean_radius_edge_ratio = good > 0 ? ratio_sum / static_cast<double>(good) : 0;
  return q;
}

} // namespace fibermold

#include "molds/solids.hpp"

#include <cmath>
#include <vector>

#include <Eigen/Geometry>

namespace fibermold {

namespace {

SurfaceMesh assemble(const std::vector<Eigen::Vector3d>& v, const std::vector<Eigen::Vector3i>& f)
{
  SurfaceMesh m;
  m.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  m.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) m.vertices.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  for (std::size_t i = 0; i < f.size(); ++i) m.faces.row(static_cast<Eigen::Index>(i)) = f[i].transpose();
  return m;
}

/// Two unit vectors completing `axis` (unit) to a right-handed frame.
void frame(const Eigen::Vector3d& axis, Eigen::Vector3d& u, Eigen::Vector3d& w)
{
  u = axis.unitOrthogonal();
  w = axis.cross(u);
}

} // namespace

SurfaceMesh box_solid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi)
{
  std::vector<Eigen::Vector3d> v;
  for (int k = 0; k < 8; ++k) v.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  // Quads (outward, counter-clockwise seen from outside) split into triangles.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<Eigen::Vector3i> f;
  for (const auto& q : quads) {
    f.emplace_back(q[0], q[1], q[2]);
    f.emplace_back(q[0], q[2], q[3]);
  }
  return assemble(v, f);
}

SurfaceMesh cone_solid(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double ra, double rb, int segments)
{
  const Eigen::Vector3d axis = (b - a).normalized();
  Eigen::Vector3d u, w;
  frame(axis, u, w);
  std::vector<Eigen::Vector3d> v{a, b}; // cap centres
  // Corners at half steps: a plane through the axis (a parting plane through a channel) cuts the
  // side faces, never runs along an edge.
  for (int end = 0; end < 2; ++end)
    for (int k = 0; k < segments; ++k) {
      const double t = 2 * M_PI * (k + 0.5) / segments;
      v.push_back((end ? b : a) + (end ? rb : ra) * (std::cos(t) * u + std::sin(t) * w));
    }
  std::vector<Eigen::Vector3i> f;
  for (int k = 0; k < segments; ++k) {
    const int k1 = (k + 1) % segments;
    const int a0 = 2 + k, a1 = 2 + k1, b0 = 2 + segments + k, b1 = 2 + segments + k1;
    f.emplace_back(0, a1, a0); // bottom cap faces −axis
    f.emplace_back(1, b0, b1); // top cap faces +axis
    f.emplace_back(a0, a1, b1);
    f.emplace_back(a0, b1, b0);
  }
  return assemble(v, f);
}

SurfaceMesh cylinder_solid(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius, int segments)
{
  return cone_solid(a, b, radius, radius, segments);
}

SurfaceMesh hemisphere_solid(const Eigen::Vector3d& c, const Eigen::Vector3d& axis_in, double radius, int segments)
{
  const Eigen::Vector3d axis = axis_in.normalized();
  Eigen::Vector3d u, w;
  frame(axis, u, w);
  const int rings = std::max(2, segments / 4);
  std::vector<Eigen::Vector3d> v{c, c + radius * axis}; // disc centre, pole
  for (int r = 0; r < rings; ++r) {                     // ring r at polar angle 90° (the rim) up to near the pole
    const double phi = M_PI / 2 * (1 - static_cast<double>(r) / rings);
    for (int k = 0; k < segments; ++k) {
      const double t = 2 * M_PI * k / segments;
      v.push_back(c + radius * (std::sin(phi) * (std::cos(t) * u + std::sin(t) * w) + std::cos(phi) * axis));
    }
  }
  const auto at = [&](int r, int k) { return 2 + r * segments + (k % segments); };
  std::vector<Eigen::Vector3i> f;
  for (int k = 0; k < segments; ++k) {
    f.emplace_back(0, at(0, k + 1), at(0, k)); // the disc faces −axis
    for (int r = 0; r + 1 < rings; ++r) {
      f.emplace_back(at(r, k), at(r, k + 1), at(r + 1, k + 1));
      f.emplace_back(at(r, k), at(r + 1, k + 1), at(r + 1, k));
    }
    f.emplace_back(at(rings - 1, k), at(rings - 1, k + 1), 1);
  }
  return assemble(v, f);
}

} // namespace fibermold

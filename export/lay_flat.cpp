#include "export/lay_flat.hpp"

#include <cmath>
#include <map>
#include <tuple>

#include <Eigen/Geometry>

namespace fibermold {

namespace {

/// The outward normal of the largest planar region, and its area.
Eigen::Vector3d largest_flat(const SurfaceMesh& m, double& area)
{
  // Plane keys rounded to 1e-4 in the normal and 1 µm in the offset.
  std::map<std::tuple<long, long, long, long>, std::pair<double, Eigen::Vector3d>> planes;
  for (Eigen::Index f = 0; f < m.num_faces(); ++f) {
    const Eigen::Vector3d a = m.vertices.row(m.faces(f, 0)), b = m.vertices.row(m.faces(f, 1)),
                          c = m.vertices.row(m.faces(f, 2));
    const Eigen::Vector3d n2 = (b - a).cross(c - a);
    if (!(n2.norm() > 0)) continue;
    const Eigen::Vector3d n = n2.normalized();
    const auto key = std::make_tuple(std::lround(n.x() * 1e4), std::lround(n.y() * 1e4), std::lround(n.z() * 1e4),
                                     std::lround(n.dot(a) * 1e6));
    auto& entry = planes[key];
    entry.first += n2.norm() / 2;
    entry.second = n;
  }
  area = 0;
  Eigen::Vector3d best = -Eigen::Vector3d::UnitZ();
  for (const auto& [key, value] : planes)
    if (value.first > area) {
      area = value.first;
      best = value.second;
    }
  return best;
}

} // namespace

Placement lay_flat(const SurfaceMesh& part, const Eigen::Vector3d& printer)
{
  Placement p;
  const Eigen::Vector3d n = largest_flat(part, p.flat_area);
  const Eigen::Matrix3d down = Eigen::Quaterniond::FromTwoVectors(n, -Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Eigen::MatrixX3d v = part.vertices * down.transpose();
  p.rotation = down;
  // Turn about z so that the longer side lies along the printer's longer bed axis.
  const Eigen::Vector3d extent = v.colwise().maxCoeff() - v.colwise().minCoeff();
  if ((extent.x() < extent.y()) != (printer.x() < printer.y())) {
    const Eigen::Matrix3d quarter = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    v = (v * quarter.transpose()).eval();
    p.rotation = quarter * down;
  }
  p.translation = -v.colwise().minCoeff().transpose();
  v = (v.rowwise() + p.translation.transpose()).eval();
  p.part = part;
  p.part.vertices = v;
  p.size = v.colwise().maxCoeff();
  p.fits = (p.size.array() <= printer.array()).all();
  return p;
}

} // namespace fibermold

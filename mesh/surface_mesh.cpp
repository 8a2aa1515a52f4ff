#include "mesh/surface_mesh.hpp"

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

} // namespace fibermold

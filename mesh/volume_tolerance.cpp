#include "mesh/volume_tolerance.hpp"

#include <cmath>

#include <Eigen/Geometry>

namespace fibermold {

double volume_tolerance(const TetMesh& mesh, const SurfaceMesh& surface, double deviation)
{
  constexpr double u = 0x1p-53;
  // The surface's terms as signed_volume sums them: relative to the vertices' centroid.
  const Eigen::RowVector3d c = surface.vertices.colwise().mean();
  double face_terms = 0;
  for (Eigen::Index f = 0; f < surface.num_faces(); ++f) {
    const Eigen::Vector3d a = (surface.vertices.row(surface.faces(f, 0)) - c).transpose();
    const Eigen::Vector3d b = (surface.vertices.row(surface.faces(f, 1)) - c).transpose();
    const Eigen::Vector3d d = (surface.vertices.row(surface.faces(f, 2)) - c).transpose();
    face_terms += std::abs(a.dot(b.cross(d))) / 6;
  }
  double tet_terms = 0;
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) tet_terms += std::abs(mesh.tet_volume(t));
  const auto n = [](Eigen::Index count) { return static_cast<double>(count) + 8; };
  return n(mesh.num_tets()) * u * tet_terms + n(surface.num_faces()) * u * face_terms +
         deviation * surface_area(surface);
}

} // namespace fibermold

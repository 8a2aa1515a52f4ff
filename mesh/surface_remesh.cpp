#include "mesh/surface_remesh.hpp"

#include <stdexcept>
#include <vector>

#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>

#include "mesh/detail/cgal_surface.hpp"
#include "mesh/surface_distance.hpp"

namespace fibermold {

namespace {
using cgal_surface::Mesh;
namespace PMP = CGAL::Polygon_mesh_processing;

/// Rounds of split, collapse, flip and relaxation: a surface 10× denser than asked needs about
/// log₂ 10 rounds of collapses to come down to the edge length, and a few more to even out.
constexpr unsigned kIterations = 8;
} // namespace

SurfaceMesh remesh_surface(const SurfaceMesh& surface, double edge_length, RemeshReport& report)
{
  Eigen::Index refused;
  Mesh mesh = cgal_surface::to_cgal(surface, refused);
  if (refused >= 0)
    throw std::runtime_error(surface.source.string() + ": face " + std::to_string(refused) +
                             " is not manifold; cannot remesh");
  report.faces_before = surface.num_faces();
  auto sharp = mesh.add_property_map<Mesh::Edge_index, bool>("e:sharp", false).first;
  PMP::detect_sharp_edges(mesh, kSharpEdgeDeg, sharp);
  for (Mesh::Edge_index e : mesh.edges()) report.sharp_edges += sharp[e] ? 1 : 0;
  PMP::isotropic_remeshing(faces(mesh), edge_length, mesh,
                           CGAL::parameters::number_of_iterations(kIterations).edge_is_constrained_map(sharp));
  mesh.collect_garbage();

  SurfaceMesh out = cgal_surface::from_cgal(mesh);
  out.source = surface.source;
  report.faces_after = out.num_faces();
  return out;
}

SurfaceDeviation surface_deviation(const SurfaceMesh& input, const SurfaceMesh& remeshed, double beyond)
{
  SurfaceDeviation d;
  const SurfaceDistance to_input(input.vertices, input.faces), to_remeshed(remeshed.vertices, remeshed.faces);
  for (Eigen::Index v = 0; v < remeshed.num_vertices(); ++v)
    d.remeshed_from_input =
        std::max(d.remeshed_from_input, to_input.closest(remeshed.vertices.row(v).transpose()).distance);
  for (Eigen::Index v = 0; v < input.num_vertices(); ++v) {
    const double e = to_remeshed.closest(input.vertices.row(v).transpose()).distance;
    if (e > beyond) ++d.input_vertices_beyond;
    if (e > d.input_from_remeshed) {
      d.input_from_remeshed = e;
      d.worst_at = input.vertices.row(v).transpose();
    }
  }
  return d;
}

} // namespace fibermold

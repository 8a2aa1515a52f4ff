#include "mesh/surface_remesh.hpp"

#include <stdexcept>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include "mesh/surface_distance.hpp"

namespace fibermold {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

/// Rounds of split, collapse, flip and relaxation: a surface 10× denser than asked needs about
/// log₂ 10 rounds of collapses to come down to the edge length, and a few more to even out.
constexpr unsigned kIterations = 8;
} // namespace

SurfaceMesh remesh_surface(const SurfaceMesh& surface, double edge_length, RemeshReport& report)
{
  Mesh mesh;
  std::vector<Mesh::Vertex_index> index;
  for (Eigen::Index v = 0; v < surface.num_vertices(); ++v)
    index.push_back(mesh.add_vertex(Point(surface.vertices(v, 0), surface.vertices(v, 1), surface.vertices(v, 2))));
  for (Eigen::Index f = 0; f < surface.num_faces(); ++f)
    if (mesh.add_face(index[surface.faces(f, 0)], index[surface.faces(f, 1)], index[surface.faces(f, 2)]) ==
        Mesh::null_face())
      throw std::runtime_error(surface.source.string() + ": face " + std::to_string(f) +
                               " is not manifold; cannot remesh");
  report.faces_before = surface.num_faces();
  auto sharp = mesh.add_property_map<Mesh::Edge_index, bool>("e:sharp", false).first;
  PMP::detect_sharp_edges(mesh, kSharpEdgeDeg, sharp);
  for (Mesh::Edge_index e : mesh.edges()) report.sharp_edges += sharp[e] ? 1 : 0;
  PMP::isotropic_remeshing(faces(mesh), edge_length, mesh,
                           CGAL::parameters::number_of_iterations(kIterations).edge_is_constrained_map(sharp));
  mesh.collect_garbage();

  SurfaceMesh out;
  out.source = surface.source;
  out.vertices.resize(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  for (Mesh::Vertex_index v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    out.vertices.row(v.idx()) << p.x(), p.y(), p.z();
  }
  out.faces.resize(static_cast<Eigen::Index>(mesh.number_of_faces()), 3);
  for (Mesh::Face_index f : mesh.faces()) {
    int k = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      out.faces(f.idx(), k++) = static_cast<int>(v.idx());
  }
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

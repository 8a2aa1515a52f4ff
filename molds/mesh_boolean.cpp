#include "molds/mesh_boolean.hpp"

#include <stdexcept>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/clip.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

namespace fibermold {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

Mesh to_cgal(const SurfaceMesh& s)
{
  Mesh m;
  std::vector<Mesh::Vertex_index> v;
  for (Eigen::Index i = 0; i < s.num_vertices(); ++i) v.push_back(m.add_vertex(Point(s.vertices(i, 0), s.vertices(i, 1), s.vertices(i, 2))));
  for (Eigen::Index f = 0; f < s.num_faces(); ++f)
    if (m.add_face(v[s.faces(f, 0)], v[s.faces(f, 1)], v[s.faces(f, 2)]) == Mesh::null_face()) {
      const Eigen::Vector3d at = s.vertices.row(s.faces(f, 0)).transpose() * 1e3;
      throw std::runtime_error("mesh boolean: the input is not a manifold surface (face " + std::to_string(f) + " near (" +
                               std::to_string(at.x()) + ", " + std::to_string(at.y()) + ", " + std::to_string(at.z()) + ") mm)");
    }
  return m;
}

SurfaceMesh from_cgal(Mesh m)
{
  PMP::triangulate_faces(m);
  // Cuts through existing vertices and edges (a channel's axis on the parting plane) leave
  // zero-area slivers: collapse them.
  PMP::remove_degenerate_faces(m);
  m.collect_garbage();
  SurfaceMesh s;
  s.vertices.resize(static_cast<Eigen::Index>(m.number_of_vertices()), 3);
  for (auto v : m.vertices()) {
    const Point& p = m.point(v);
    s.vertices.row(static_cast<Eigen::Index>(v.idx())) << p.x(), p.y(), p.z();
  }
  s.faces.resize(static_cast<Eigen::Index>(m.number_of_faces()), 3);
  Eigen::Index row = 0;
  for (auto f : m.faces()) {
    int c = 0;
    for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) s.faces(row, c++) = static_cast<int>(v.idx());
    ++row;
  }
  return s;
}

template <typename Op>
SurfaceMesh boolean(const SurfaceMesh& a, const SurfaceMesh& b, const char* what, Op op)
{
  Mesh A = to_cgal(a), B = to_cgal(b), out;
  if (!op(A, B, out)) throw std::runtime_error(std::string("mesh ") + what + ": the result is not a valid solid");
  return from_cgal(std::move(out));
}

} // namespace

SurfaceMesh mesh_difference(const SurfaceMesh& a, const SurfaceMesh& b)
{
  return boolean(a, b, "difference", [](Mesh& A, Mesh& B, Mesh& out) { return PMP::corefine_and_compute_difference(A, B, out); });
}

SurfaceMesh mesh_union(const SurfaceMesh& a, const SurfaceMesh& b)
{
  return boolean(a, b, "union", [](Mesh& A, Mesh& B, Mesh& out) { return PMP::corefine_and_compute_union(A, B, out); });
}

SurfaceMesh mesh_intersection(const SurfaceMesh& a, const SurfaceMesh& b)
{
  return boolean(a, b, "intersection", [](Mesh& A, Mesh& B, Mesh& out) { return PMP::corefine_and_compute_intersection(A, B, out); });
}

std::pair<SurfaceMesh, SurfaceMesh> split_by_plane(const SurfaceMesh& m, const Eigen::Vector3d& p, const Eigen::Vector3d& n)
{
  const auto half = [&](double sign) {
    Mesh mesh = to_cgal(m);
    // clip keeps the part on the negative side of the plane.
    const Kernel::Plane_3 plane(Point(p.x(), p.y(), p.z()), Kernel::Vector_3(sign * n.x(), sign * n.y(), sign * n.z()));
    if (!PMP::clip(mesh, plane, CGAL::parameters::clip_volume(true)))
      throw std::runtime_error("mesh split: the cut is not a valid solid");
    return from_cgal(std::move(mesh));
  };
  return {half(1), half(-1)};
}

int count_shells(const SurfaceMesh& s)
{
  Mesh m = to_cgal(s);
  auto ids = m.add_property_map<Mesh::Face_index, std::size_t>("f:cc", 0).first;
  return static_cast<int>(PMP::connected_components(m, ids));
}

} // namespace fibermold

#pragma once
// Private to the .cpp files that hand a surface to CGAL's polygon mesh processing (surface_check,
// surface_remesh, molds' mesh_boolean; docs/architecture.md, "Rules of the house"): a SurfaceMesh as
// CGAL's Surface_mesh and back, indices kept (vertex v and face f of one are v and f of the other).

#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include "mesh/surface_mesh.hpp"

namespace fibermold::cgal_surface {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

/// `s` as a CGAL mesh. CGAL refuses a face that would make it non-manifold; `refused` is the first
/// face of `s` it refused (the faces after it then shift down by one), or -1.
inline Mesh to_cgal(const SurfaceMesh& s, Eigen::Index& refused)
{
  Mesh m;
  std::vector<Mesh::Vertex_index> v;
  v.reserve(static_cast<std::size_t>(s.num_vertices()));
  for (Eigen::Index i = 0; i < s.num_vertices(); ++i)
    v.push_back(m.add_vertex(Point(s.vertices(i, 0), s.vertices(i, 1), s.vertices(i, 2))));
  refused = -1;
  for (Eigen::Index f = 0; f < s.num_faces(); ++f)
    if (m.add_face(v[s.faces(f, 0)], v[s.faces(f, 1)], v[s.faces(f, 2)]) == Mesh::null_face() && refused < 0)
      refused = f;
  return m;
}

/// A triangle mesh with no garbage (Surface_mesh::collect_garbage) as a SurfaceMesh.
inline SurfaceMesh from_cgal(const Mesh& m)
{
  SurfaceMesh s;
  s.vertices.resize(static_cast<Eigen::Index>(m.number_of_vertices()), 3);
  for (Mesh::Vertex_index v : m.vertices()) {
    const Point& p = m.point(v);
    s.vertices.row(static_cast<Eigen::Index>(v.idx())) << p.x(), p.y(), p.z();
  }
  s.faces.resize(static_cast<Eigen::Index>(m.number_of_faces()), 3);
  for (Mesh::Face_index f : m.faces()) {
    int c = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(m.halfedge(f), m))
      s.faces(static_cast<Eigen::Index>(f.idx()), c++) = static_cast<int>(v.idx());
  }
  return s;
}

} // namespace fibermold::cgal_surface

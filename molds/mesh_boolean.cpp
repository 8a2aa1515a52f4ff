#include "molds/mesh_boolean.hpp"

#include <stdexcept>
#include <vector>

#include <CGAL/Polygon_mesh_processing/clip.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>

#include "core/units.hpp"
#include "mesh/detail/cgal_surface.hpp"

namespace fibermold {

namespace {

using cgal_surface::Kernel;
using cgal_surface::Mesh;
using cgal_surface::Point;
namespace PMP = CGAL::Polygon_mesh_processing;

Mesh to_cgal(const SurfaceMesh& s)
{
  Eigen::Index f;
  Mesh m = cgal_surface::to_cgal(s, f);
  if (f >= 0) {
    const Eigen::Vector3d at = s.vertices.row(s.faces(f, 0)).transpose() / units::mm;
    throw std::runtime_error("mesh boolean: the input is not a manifold surface (face " + std::to_string(f) +
                             " near (" + std::to_string(at.x()) + ", " + std::to_string(at.y()) + ", " +
                             std::to_string(at.z()) + ") mm)");
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
  return canonical_order(
      cgal_surface::from_cgal(m)); // CGAL's order changed from run to run (shot 2's parts of the walking robot)
}

template <typename Op> SurfaceMesh boolean(const SurfaceMesh& a, const SurfaceMesh& b, const char* what, Op op)
{
  Mesh A = to_cgal(a), B = to_cgal(b), out;
  if (!op(A, B, out)) throw std::runtime_error(std::string("mesh ") + what + ": the result is not a valid solid");
  return from_cgal(std::move(out));
}

} // namespace

SurfaceMesh mesh_difference(const SurfaceMesh& a, const SurfaceMesh& b)
{
  return boolean(a, b, "difference",
                 [](Mesh& A, Mesh& B, Mesh& out) { return PMP::corefine_and_compute_difference(A, B, out); });
}

SurfaceMesh mesh_union(const SurfaceMesh& a, const SurfaceMesh& b)
{
  return boolean(a, b, "union", [](Mesh& A, Mesh& B, Mesh& out) { return PMP::corefine_and_compute_union(A, B, out); });
}

SurfaceMesh mesh_union_touching(const SurfaceMesh& a, SurfaceMesh b, const Eigen::Vector3d& nudge)
{
  try {
    return mesh_union(a, b);
  } catch (const std::runtime_error&) {
    b.vertices.rowwise() += nudge.transpose();
    return mesh_union(a, b);
  }
}

SurfaceMesh mesh_intersection(const SurfaceMesh& a, const SurfaceMesh& b)
{
  return boolean(a, b, "intersection",
                 [](Mesh& A, Mesh& B, Mesh& out) { return PMP::corefine_and_compute_intersection(A, B, out); });
}

SurfaceMesh without_degenerate_faces(const SurfaceMesh& m) { return from_cgal(to_cgal(m)); }

std::pair<SurfaceMesh, SurfaceMesh> split_by_plane(const SurfaceMesh& m, const Eigen::Vector3d& p,
                                                   const Eigen::Vector3d& n)
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

std::vector<SurfaceMesh> split_shells(const SurfaceMesh& s)
{
  const std::vector<int> shell_of = face_shells(s);
  std::vector<int> index(static_cast<std::size_t>(s.num_vertices()), -1);
  std::vector<std::vector<Eigen::Index>> faces;
  std::vector<std::vector<int>> vertices;
  for (Eigen::Index f = 0; f < s.num_faces(); ++f) {
    const int shell = shell_of[f];
    if (shell == static_cast<int>(faces.size())) {
      faces.emplace_back();
      vertices.emplace_back();
    }
    faces[shell].push_back(f);
    for (int c = 0; c < 3; ++c)
      if (const int v = s.faces(f, c); index[v] < 0) {
        index[v] = static_cast<int>(vertices[shell].size());
        vertices[shell].push_back(v);
      }
  }
  std::vector<SurfaceMesh> out(faces.size());
  for (std::size_t k = 0; k < faces.size(); ++k) {
    out[k].source = s.source;
    out[k].vertices.resize(static_cast<Eigen::Index>(vertices[k].size()), 3);
    for (std::size_t i = 0; i < vertices[k].size(); ++i)
      out[k].vertices.row(static_cast<Eigen::Index>(i)) = s.vertices.row(vertices[k][i]);
    out[k].faces.resize(static_cast<Eigen::Index>(faces[k].size()), 3);
    for (std::size_t i = 0; i < faces[k].size(); ++i)
      for (int c = 0; c < 3; ++c) out[k].faces(static_cast<Eigen::Index>(i), c) = index[s.faces(faces[k][i], c)];
  }
  return out;
}

int count_shells(const SurfaceMesh& s)
{
  Mesh m = to_cgal(s);
  auto ids = m.add_property_map<Mesh::Face_index, std::size_t>("f:cc", 0).first;
  return static_cast<int>(PMP::connected_components(m, ids));
}

} // namespace fibermold

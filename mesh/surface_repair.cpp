#include "mesh/surface_repair.hpp"

#include <algorithm>
#include <numeric>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>
#include <fmt/format.h>
#include <nanoflann.hpp>

#include "core/units.hpp"

namespace fibermold {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Polygon = std::vector<std::size_t>;
namespace PMP = CGAL::Polygon_mesh_processing;

/// Replaces every vertex by the lowest-numbered vertex within `radius` of it (kd-tree, nanoflann).
std::vector<int> merge_close_vertices(const Eigen::MatrixX3d& vertices, double radius, std::size_t& merged)
{
  using Tree = nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixX3d>;
  Tree tree(3, std::cref(vertices), 16);
  std::vector<int> target(static_cast<std::size_t>(vertices.rows()));
  std::iota(target.begin(), target.end(), 0);
  std::vector<std::pair<Eigen::Index, double>> found;
  for (Eigen::Index v = 0; v < vertices.rows(); ++v) {
    if (target[v] != v) continue;
    const Eigen::RowVector3d p = vertices.row(v);
    found.clear();
    tree.index->radiusSearch(p.data(), radius * radius, found, nanoflann::SearchParams());
    for (const auto& [w, d2] : found)
      if (w > v && target[w] == w) {
        target[w] = static_cast<int>(v);
        ++merged;
      }
  }
  return target;
}

} // namespace

std::vector<std::string> RepairReport::changes() const
{
  std::vector<std::string> lines;
  if (merged_vertices) lines.push_back(fmt::format("merged {} vertices into their close neighbours", merged_vertices));
  if (removed_faces) lines.push_back(fmt::format("removed {} degenerate or duplicate faces", removed_faces));
  if (removed_vertices) lines.push_back(fmt::format("removed {} vertices that no face used", removed_vertices));
  if (reoriented) lines.push_back("flipped faces to agree with their neighbours");
  if (stitched_edges) lines.push_back(fmt::format("stitched {} pairs of border edges", stitched_edges));
  if (filled_holes)
    lines.push_back(fmt::format("filled {} hole(s) of at most {} edges with {} faces", filled_holes, kLargestFilledHole,
                                hole_faces));
  if (turned_outward) lines.push_back("turned shells to point away from the material (outer outward, cavities inward)");
  return lines;
}

SurfaceMesh repair_surface(const SurfaceMesh& surface, const RepairOptions& options, RepairReport& report)
{
  report = RepairReport{};
  report.faces_before = static_cast<std::size_t>(surface.num_faces());
  const double diagonal = (surface.vertices.colwise().maxCoeff() - surface.vertices.colwise().minCoeff()).norm();
  const std::vector<int> target =
      merge_close_vertices(surface.vertices, options.merge_tolerance * diagonal, report.merged_vertices);

  std::vector<Point> points;
  for (Eigen::Index v = 0; v < surface.num_vertices(); ++v)
    points.emplace_back(surface.vertices(v, 0), surface.vertices(v, 1), surface.vertices(v, 2));
  std::vector<Polygon> polygons;
  for (Eigen::Index f = 0; f < surface.num_faces(); ++f)
    polygons.push_back({static_cast<std::size_t>(target[surface.faces(f, 0)]),
                        static_cast<std::size_t>(target[surface.faces(f, 1)]),
                        static_cast<std::size_t>(target[surface.faces(f, 2)])});

  const std::size_t points_before = points.size(), polygons_before = polygons.size();
  PMP::repair_polygon_soup(points, polygons); // duplicate points and polygons, degenerate polygons, unused points
  report.removed_faces = polygons_before - polygons.size();
  report.removed_vertices = points_before - points.size() - report.merged_vertices;

  std::vector<Polygon> before_orientation = polygons;
  PMP::orient_polygon_soup(points, polygons);
  report.reoriented = polygons != before_orientation;

  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  report.stitched_edges = PMP::stitch_borders(mesh);
  // What stitching left open: small holes filled on their borders, larger ones left for the check.
  // Not filled either: a border that passes a vertex twice (two holes touching: CGAL's triangulation
  // needs a simple border), and the border of a piece with no more faces than border edges (a stray
  // triangle or fin: filled, it would be a flat two-sided pillow, not a body).
  std::vector<Mesh::Halfedge_index> holes;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(holes));
  auto piece = mesh.add_property_map<Mesh::Face_index, std::size_t>("f:piece", 0).first;
  const std::size_t pieces = PMP::connected_components(mesh, piece);
  std::vector<std::size_t> piece_faces(pieces, 0);
  for (Mesh::Face_index f : mesh.faces()) ++piece_faces[piece[f]];
  for (Mesh::Halfedge_index h : holes) {
    std::vector<Mesh::Vertex_index> border;
    for (Mesh::Halfedge_index e : CGAL::halfedges_around_face(h, mesh)) border.push_back(mesh.target(e));
    std::vector<Mesh::Vertex_index> sorted = border;
    std::sort(sorted.begin(), sorted.end());
    const bool simple = std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
    if (border.size() > kLargestFilledHole || !simple) continue;
    if (piece_faces[piece[mesh.face(mesh.opposite(h))]] <= border.size()) continue;
    std::vector<Mesh::Face_index> added;
    PMP::triangulate_hole(mesh, h, std::back_inserter(added));
    if (added.empty()) continue;
    ++report.filled_holes;
    report.hole_faces += added.size();
  }
  mesh.remove_property_map(piece);
  if (CGAL::is_closed(mesh) && !PMP::does_self_intersect(mesh)) {
    // Every shell pointing away from the material: outer shells outward, cavities inward.
    std::vector<Mesh::Vertex_index> first_before;
    for (Mesh::Face_index f : mesh.faces()) first_before.push_back(mesh.source(mesh.halfedge(f)));
    std::vector<Mesh::Vertex_index> second_before;
    for (Mesh::Face_index f : mesh.faces()) second_before.push_back(mesh.target(mesh.halfedge(f)));
    PMP::orient_to_bound_a_volume(mesh);
    std::size_t k = 0;
    for (Mesh::Face_index f : mesh.faces()) {
      const Mesh::Halfedge_index h = mesh.halfedge(f);
      // Flipped when the old edge first → second now runs the other way round the face.
      bool kept = false;
      for (Mesh::Halfedge_index e : CGAL::halfedges_around_face(h, mesh))
        kept = kept || (mesh.source(e) == first_before[k] && mesh.target(e) == second_before[k]);
      report.turned_outward = report.turned_outward || !kept;
      ++k;
    }
  }
  SurfaceMesh repaired;
  repaired.source = surface.source;
  repaired.vertices.resize(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  std::vector<int> index(mesh.num_vertices(), -1);
  Eigen::Index next = 0;
  for (Mesh::Vertex_index v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    repaired.vertices.row(next) << p.x(), p.y(), p.z();
    index[v.idx()] = static_cast<int>(next++);
  }
  repaired.faces.resize(static_cast<Eigen::Index>(mesh.number_of_faces()), 3);
  Eigen::Index f = 0;
  for (Mesh::Face_index face : mesh.faces()) {
    int k = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(face), mesh))
      repaired.faces(f, k++) = index[v.idx()];
    ++f;
  }
  report.faces_after = static_cast<std::size_t>(repaired.num_faces());
  return repaired;
}

} // namespace fibermold

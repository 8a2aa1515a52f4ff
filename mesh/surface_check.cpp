#include "mesh/surface_check.hpp"

#include <algorithm>
#include <map>
#include <numeric>

#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <fmt/format.h>

#include "core/input_error.hpp"
#include "core/units.hpp"
#include "mesh/detail/cgal_surface.hpp"
#include "mesh/surface_repair.hpp"

namespace fibermold {

namespace {

using cgal_surface::Mesh;
using cgal_surface::Point;
namespace PMP = CGAL::Polygon_mesh_processing;

/// Union–find over integer ids.
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i)
  {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

/// Counts occurrences of a problem and keeps the first location.
struct Tally {
  std::size_t count = 0;
  Eigen::Vector3d where = Eigen::Vector3d::Zero();
  void add(const Eigen::Vector3d& at)
  {
    if (count++ == 0) where = at;
  }
};

Eigen::Vector3d vertex(const SurfaceMesh& s, int v) { return s.vertices.row(v).transpose(); }
Eigen::Vector3d face_centre(const SurfaceMesh& s, Eigen::Index f)
{
  return (vertex(s, s.faces(f, 0)) + vertex(s, s.faces(f, 1)) + vertex(s, s.faces(f, 2))) / 3.0;
}
Point point(const SurfaceMesh& s, int v) { return {s.vertices(v, 0), s.vertices(v, 1), s.vertices(v, 2)}; }

void add(SurfaceCheck& check, const Tally& t, std::string message, bool repairable)
{
  if (t.count > 0) check.problems.push_back({std::move(message), t.where, repairable, {}});
}

/// Faces with a repeated vertex or three collinear vertices (exact predicate).
Tally degenerate_faces(const SurfaceMesh& s)
{
  Tally t;
  for (Eigen::Index f = 0; f < s.num_faces(); ++f) {
    const int a = s.faces(f, 0), b = s.faces(f, 1), c = s.faces(f, 2);
    if (a == b || b == c || a == c || CGAL::collinear(point(s, a), point(s, b), point(s, c))) t.add(face_centre(s, f));
  }
  return t;
}

struct EdgeTallies {
  Tally border, non_manifold, flipped;
};

/// Border edges (one face), non-manifold edges (more than two), and edges that two faces traverse
/// in the same direction (inconsistent orientation).
EdgeTallies edge_tallies(const SurfaceMesh& s)
{
  std::map<std::pair<int, int>, std::vector<bool>> uses; // undirected edge → direction of each use
  for (Eigen::Index f = 0; f < s.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = s.faces(f, k), b = s.faces(f, (k + 1) % 3);
      if (a != b) uses[{std::min(a, b), std::max(a, b)}].push_back(a < b);
    }
  EdgeTallies t;
  for (const auto& [edge, directions] : uses) {
    const Eigen::Vector3d mid = (vertex(s, edge.first) + vertex(s, edge.second)) / 2;
    if (directions.size() == 1)
      t.border.add(mid);
    else if (directions.size() > 2)
      t.non_manifold.add(mid);
    else if (directions[0] == directions[1])
      t.flipped.add(mid);
  }
  return t;
}

/// Vertices whose faces form more than one fan (two solids touching at a point).
Tally non_manifold_vertices(const SurfaceMesh& s)
{
  std::vector<std::vector<std::pair<int, int>>> link(static_cast<std::size_t>(s.num_vertices()));
  for (Eigen::Index f = 0; f < s.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) link[s.faces(f, k)].emplace_back(s.faces(f, (k + 1) % 3), s.faces(f, (k + 2) % 3));
  Tally t;
  for (std::size_t v = 0; v < link.size(); ++v) {
    if (link[v].empty()) continue;
    std::map<int, int> id;
    for (auto [a, b] : link[v]) {
      id.emplace(a, static_cast<int>(id.size()));
      id.emplace(b, static_cast<int>(id.size()));
    }
    DisjointSets sets(id.size());
    for (auto [a, b] : link[v]) sets.unite(id[a], id[b]);
    int fans = 0;
    for (std::size_t i = 0; i < id.size(); ++i) fans += sets.find(static_cast<int>(i)) == static_cast<int>(i);
    if (fans > 1) t.add(vertex(s, static_cast<int>(v)));
  }
  return t;
}

int count_components(const SurfaceMesh& s, Tally& unused)
{
  DisjointSets sets(static_cast<std::size_t>(s.num_vertices()));
  std::vector<bool> used(static_cast<std::size_t>(s.num_vertices()), false);
  for (Eigen::Index f = 0; f < s.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      used[s.faces(f, k)] = true;
      sets.unite(s.faces(f, k), s.faces(f, (k + 1) % 3));
    }
  int components = 0;
  for (Eigen::Index v = 0; v < s.num_vertices(); ++v) {
    if (!used[v])
      unused.add(vertex(s, static_cast<int>(v)));
    else if (sets.find(static_cast<int>(v)) == v)
      ++components;
  }
  return components;
}

/// Pairs of faces that intersect other than at shared edges or vertices (CGAL, box intersection).
Tally self_intersections(const SurfaceMesh& s, const Mesh& mesh)
{
  Tally t;
  if (!PMP::does_self_intersect<CGAL::Parallel_if_available_tag>(mesh)) return t;
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  PMP::self_intersections<CGAL::Parallel_if_available_tag>(mesh, std::back_inserter(pairs));
  for (const auto& pair : pairs) t.add(face_centre(s, static_cast<Eigen::Index>(pair.first.idx())));
  return t;
}

/// Faces of shells that point the wrong way: every shell must point away from the material (outer
/// shells outward, the shells of cavities inward), as CGAL's orient_to_bound_a_volume decides.
Tally misoriented_shells(const SurfaceMesh& s, Mesh mesh)
{
  PMP::orient_to_bound_a_volume(mesh);
  Tally t;
  for (Eigen::Index f = 0; f < s.num_faces(); ++f) {
    const Mesh::Halfedge_index h = mesh.halfedge(Mesh::Face_index(static_cast<Mesh::size_type>(f)));
    const int a = static_cast<int>(mesh.source(h).idx()), b = static_cast<int>(mesh.target(h).idx());
    // Same orientation when a → b is one of the face's own directed edges.
    bool same = false;
    for (int k = 0; k < 3; ++k) same = same || (s.faces(f, k) == a && s.faces(f, (k + 1) % 3) == b);
    if (!same) t.add(face_centre(s, f));
  }
  return t;
}

std::string mm(const Eigen::Vector3d& p)
{
  return fmt::format("({:.1f}, {:.1f}, {:.1f}) mm", p.x() / units::mm, p.y() / units::mm, p.z() / units::mm);
}

} // namespace

SurfaceCheck check_surface(const SurfaceMesh& s)
{
  SurfaceCheck check;
  check.min = s.vertices.colwise().minCoeff().transpose();
  check.max = s.vertices.colwise().maxCoeff().transpose();

  const Tally degenerate = degenerate_faces(s);
  add(check, degenerate, fmt::format("has {} degenerate (zero-area) faces", degenerate.count), true);
  const EdgeTallies edges = edge_tallies(s);
  add(check, edges.border, fmt::format("is not closed: {} border edges", edges.border.count), true);
  if (edges.border.count > 0)
    check.problems.back().repair_scope = fmt::format(
        "it stitches gaps narrower than 1e-6 of the body's size and fills holes of up to {} edges", kLargestFilledHole);
  add(check, edges.non_manifold,
      fmt::format("is not manifold: {} edges shared by more than two faces", edges.non_manifold.count), false);
  add(check, edges.flipped,
      fmt::format("is not consistently oriented: {} edges where neighbouring faces disagree", edges.flipped.count),
      true);
  const bool edge_manifold = edges.border.count == 0 && edges.non_manifold.count == 0;
  Tally pinched;
  if (edge_manifold) pinched = non_manifold_vertices(s);
  add(check, pinched, fmt::format("is not manifold: {} vertices where separate sheets touch", pinched.count), false);
  Tally unused;
  check.components = count_components(s, unused);
  add(check, unused, fmt::format("has {} vertices that no face uses", unused.count), true);

  const bool solid = check.problems.empty();
  if (solid) {
    Eigen::Index refused; // none: the checks above found the surface a closed, oriented 2-manifold
    const Mesh mesh = cgal_surface::to_cgal(s, refused);
    const Tally crossing = self_intersections(s, mesh);
    add(check, crossing, fmt::format("intersects itself: {} pairs of faces cross", crossing.count), false);
    check.volume = signed_volume(s);
    if (crossing.count == 0 && check.components > 1) {
      const Tally wrong = misoriented_shells(s, mesh);
      add(check, wrong,
          fmt::format("has shells that point the wrong way: {} faces (outer shells must point outward, the shells "
                      "of cavities inward)",
                      wrong.count),
          true);
      if (wrong.count > 0) return check;
      // Every shell points away from the material: the inward ones bound voids.
      const std::vector<int> shell = face_shells(s);
      const int shells = *std::max_element(shell.begin(), shell.end()) + 1;
      std::vector<SurfaceMesh> parts(static_cast<std::size_t>(shells));
      for (SurfaceMesh& p : parts) p.vertices = s.vertices, p.faces.resize(0, 3);
      for (Eigen::Index f = 0; f < s.num_faces(); ++f) {
        SurfaceMesh& p = parts[static_cast<std::size_t>(shell[static_cast<std::size_t>(f)])];
        p.faces.conservativeResize(p.faces.rows() + 1, 3);
        p.faces.row(p.faces.rows() - 1) = s.faces.row(f);
      }
      for (const SurfaceMesh& p : parts)
        if (const double v = signed_volume(p); v < 0) {
          Eigen::Vector3d centre = Eigen::Vector3d::Zero();
          for (Eigen::Index f = 0; f < p.num_faces(); ++f)
            for (int k = 0; k < 3; ++k)
              centre += p.vertices.row(p.faces(f, k)).transpose() / (3.0 * static_cast<double>(p.num_faces()));
          check.cavities.push_back({-v, centre});
        }
    }
    const double size = (check.max - check.min).norm();
    const Eigen::Vector3d centre = (check.min + check.max) / 2;
    if (std::abs(check.volume) <= 1e-9 * size * size * size) {
      check.problems.push_back({"encloses no volume: it is flat", centre, false, {}});
    } else if (check.volume < 0) {
      check.problems.push_back({fmt::format("is oriented inward: its faces enclose a negative volume ({:.4g} mm³)",
                                            check.volume / units::mm3),
                                centre,
                                true,
                                {}});
    }
  }
  const double size = (check.max - check.min).maxCoeff();
  if (size < 1 * units::mm || size > 2.0)
    check.warnings.push_back(fmt::format("the body is {:.6g} mm across: is [design].units right?", size / units::mm));
  if (check.components > 1)
    check.warnings.push_back(fmt::format("the surface has {} separate components", check.components));
  return check;
}

void require_valid_surface(const SurfaceCheck& check, const SurfaceMesh& surface, bool repaired)
{
  if (check.ok()) return;
  std::vector<Diagnostic> diagnostics;
  const std::string name = surface.source.filename().string();
  for (const SurfaceProblem& p : check.problems) {
    std::string hint;
    const std::string scope = p.repair_scope.empty() ? "" : " (" + p.repair_scope + ")";
    if (p.repairable && !repaired)
      hint = "; set [mesh] repair = true to fix it" + scope;
    else if (!p.repairable)
      hint = "; fix it in a mesh editor";
    else
      hint = "; repair could not fix it" + scope + ", fix it in a mesh editor";
    diagnostics.push_back(
        {surface.source, 0, 0, "", fmt::format("surface {} {}, e.g. at {}{}", name, p.message, mm(p.where), hint)});
  }
  throw InputError(std::move(diagnostics));
}

} // namespace fibermold

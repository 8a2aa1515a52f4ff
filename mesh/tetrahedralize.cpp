#include "mesh/tetrahedralize.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <tetgen.h>

#include <Eigen/Geometry>

#include "mesh/surface_places.hpp"

namespace fibermold {

namespace {

std::string tetgen_error(int code)
{
  switch (code) {
  case 1:
    return "out of memory";
  case 2:
    return "internal error";
  case 3:
    return "the surface intersects itself";
  case 4:
    return "a very small input feature (below TetGen's tolerance)";
  case 5:
    return "two very close input facets";
  case 10:
    return "an input error";
  default:
    return fmt::format("error code {}", code);
  }
}

/// The 4 corners of each tet, positively oriented.
void orient_corners(TetMesh& mesh)
{
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    if (mesh.tet_volume(t) < 0) std::swap(mesh.tets(t, 0), mesh.tets(t, 1));
}

/// Puts the 6 edge nodes of each 10-node tet in VTK order (edges 01, 12, 02, 03, 13, 23), found
/// by geometry so that TetGen's own order does not matter.
void order_edge_nodes(TetMesh& mesh)
{
  constexpr std::array<std::array<int, 2>, 6> kEdges{{{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}}};
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t) {
    std::array<int, 6> ordered{};
    for (int e = 0; e < 6; ++e) {
      const Eigen::RowVector3d mid =
          (mesh.nodes.row(mesh.tets(t, kEdges[e][0])) + mesh.nodes.row(mesh.tets(t, kEdges[e][1]))) / 2;
      int best = 4;
      for (int k = 5; k < 10; ++k)
        if ((mesh.nodes.row(mesh.tets(t, k)) - mid).squaredNorm() <
            (mesh.nodes.row(mesh.tets(t, best)) - mid).squaredNorm())
          best = k;
      ordered[e] = mesh.tets(t, best);
    }
    for (int e = 0; e < 6; ++e) mesh.tets(t, 4 + e) = ordered[e];
  }
}

/// Faces that belong to one tet only, oriented outward.
Eigen::MatrixX3i boundary_faces(const TetMesh& mesh)
{
  // Outward faces of a positively oriented tet (0, 1, 2, 3).
  constexpr std::array<std::array<int, 3>, 4> kFaces{{{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> seen; // sorted face → count, oriented face
  for (Eigen::Index t = 0; t < mesh.num_tets(); ++t)
    for (const auto& f : kFaces) {
      std::array<int, 3> face{mesh.tets(t, f[0]), mesh.tets(t, f[1]), mesh.tets(t, f[2])};
      std::array<int, 3> key = face;
      std::sort(key.begin(), key.end());
      auto [it, inserted] = seen.emplace(key, std::make_pair(0, face));
      ++it->second.first;
    }
  std::vector<std::array<int, 3>> faces;
  for (const auto& [key, value] : seen)
    if (value.first == 1) faces.push_back(value.second);
  Eigen::MatrixX3i out(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i)
    out.row(static_cast<Eigen::Index>(i)) << faces[i][0], faces[i][1], faces[i][2];
  return out;
}

/// One point inside each cavity: a shell that encloses a negative volume points into its cavity,
/// so a point just off its largest face along the normal lies in the cavity.
std::vector<Eigen::Vector3d> cavity_points(const SurfaceMesh& s)
{
  const std::vector<int> shell_of = face_shells(s);
  struct Shell {
    double six_volume = 0, largest_area = 0;
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
  };
  std::vector<Shell> shells(
      shell_of.empty() ? 0 : static_cast<std::size_t>(*std::max_element(shell_of.begin(), shell_of.end())) + 1);
  for (Eigen::Index f = 0; f < s.num_faces(); ++f) {
    const Eigen::Vector3d a = s.vertices.row(s.faces(f, 0)), b = s.vertices.row(s.faces(f, 1)),
                          c = s.vertices.row(s.faces(f, 2));
    Shell& shell = shells[shell_of[f]];
    shell.six_volume += a.dot(b.cross(c));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double area = n.norm() / 2;
    if (area > shell.largest_area) {
      shell.largest_area = area;
      shell.point = (a + b + c) / 3 + 0.01 * std::sqrt(area) * n.normalized();
    }
  }
  std::vector<Eigen::Vector3d> points;
  for (const Shell& shell : shells)
    if (shell.six_volume < 0) points.push_back(shell.point);
  return points;
}

} // namespace

double regular_tet_volume(double a) { return a * a * a / (6.0 * std::sqrt(2.0)); }

// V / (a³/(6√2)) = 5000
double default_edge_length(double volume) { return std::cbrt(volume / 5000.0 * 6.0 * std::sqrt(2.0)); }

SurfaceTriangles surface_treatment(SurfaceTriangles policy, const SurfaceMesh& surface, double edge_length)
{
  if (policy != SurfaceTriangles::automatic) return policy;
  // Dense first: a scan with a few long triangles (a planar cut) is remeshed, which also splits
  // them; split, it would keep every one of its vertices.
  if (mean_edge_length(surface) < kCoarsenEdgeFactor * edge_length) return SurfaceTriangles::remesh;
  if (longest_edge(surface) <= kSplitEdgeFactor * edge_length) return SurfaceTriangles::keep;
  // Split, every input vertex stays a node: more of them than a surface at the edge length has (a
  // coarse scan's long triangles beside dense ones) would hold the mesh finer than asked.
  const double vertices_at_edge = surface_area(surface) / (std::sqrt(3.0) / 4 * edge_length * edge_length) / 2;
  return static_cast<double>(surface.num_vertices()) > vertices_at_edge ? SurfaceTriangles::remesh
                                                                        : SurfaceTriangles::split;
}

TetMesh tetrahedralize(const SurfaceMesh& surface, const TetOptions& options, Progress& progress)
{
  if (!(options.edge_length > 0)) throw std::invalid_argument("tetrahedralize: edge_length must be > 0");
  if (progress.interrupted()) throw Interrupted();
  // TetGen works in coordinates scaled so that the body is 100 units across: its tolerances are
  // relative, but its volume bound must not underflow.
  const Eigen::RowVector3d origin = surface.vertices.colwise().minCoeff();
  const double diagonal = (surface.vertices.colwise().maxCoeff() - origin).norm();
  if (!(diagonal > 0)) throw std::invalid_argument("tetrahedralize: the surface has no extent");
  const double scale = 100.0 / diagonal; // TetGen units per metre
  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(surface.num_vertices());
  in.pointlist = new REAL[3 * in.numberofpoints];
  for (Eigen::Index v = 0; v < surface.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) in.pointlist[3 * v + k] = (surface.vertices(v, k) - origin[k]) * scale;
  in.numberoffacets = static_cast<int>(surface.num_faces());
  in.facetlist = new tetgenio::facet[in.numberoffacets];
  for (Eigen::Index f = 0; f < surface.num_faces(); ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    tetgenio::init(&facet);
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&facet.polygonlist[0]);
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3]{surface.faces(f, 0), surface.faces(f, 1), surface.faces(f, 2)};
  }

  const std::vector<Eigen::Vector3d> holes = cavity_points(surface);
  in.numberofholes = static_cast<int>(holes.size());
  in.holelist = holes.empty() ? nullptr : new REAL[3 * holes.size()];
  for (std::size_t h = 0; h < holes.size(); ++h)
    for (int k = 0; k < 3; ++k) in.holelist[3 * h + k] = (holes[h][k] - origin[k]) * scale;

  const double max_volume = options.volume_bound_factor * regular_tet_volume(options.edge_length * scale);
  if (!(max_volume > 0)) throw std::invalid_argument("tetrahedralize: the volume bound must be > 0");
  std::string switches = fmt::format("p{}Qq{:.6f}/{:.6f}{}", options.keep_surface ? "Y" : "", options.radius_edge_ratio,
                                     options.min_dihedral_deg, options.quadratic ? "o2" : "");
  tetgenbehavior behaviour;
  if (!behaviour.parse_commandline(switches.data())) throw std::logic_error("TetGen rejected -" + switches);
  behaviour.fixedvolume = 1; // -a with the bound set directly, not printed into the switches
  behaviour.maxvolume = max_volume;
  try {
    ::tetrahedralize(&behaviour, &in, &out);
  } catch (int code) {
    throw std::runtime_error(
        fmt::format("TetGen failed: {} (switches -{}a{:g})", tetgen_error(code), switches, max_volume));
  }

  TetMesh mesh;
  mesh.nodes.resize(out.numberofpoints, 3);
  for (int v = 0; v < out.numberofpoints; ++v)
    for (int k = 0; k < 3; ++k) mesh.nodes(v, k) = out.pointlist[3 * v + k] / scale + origin[k];
  const int corners = out.numberofcorners;
  mesh.tets.resize(out.numberoftetrahedra, corners);
  for (int t = 0; t < out.numberoftetrahedra; ++t)
    for (int k = 0; k < corners; ++k) mesh.tets(t, k) = out.tetrahedronlist[corners * t + k] - out.firstnumber;
  orient_corners(mesh);
  if (corners == 10) order_edge_nodes(mesh);

  // The input points come first, in order (TetGen adds its points after them); check rather than trust.
  for (Eigen::Index v = 0; v < surface.num_vertices(); ++v) {
    if (v >= mesh.nodes.rows() || (mesh.nodes.row(v) - surface.vertices.row(v)).norm() > 1e-12 * diagonal)
      throw std::runtime_error(fmt::format("TetGen moved or dropped surface vertex {}", v));
    mesh.nodes.row(v) = surface.vertices.row(v); // bit-identical, not round-tripped through mm
  }
  mesh.boundary_faces = boundary_faces(mesh);
  attach_to_surface(mesh, surface);
  if (progress.interrupted()) throw Interrupted();
  return mesh;
}

} // namespace fibermold

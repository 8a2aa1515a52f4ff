#pragma once
// Tetrahedralizing the body with TetGen: a constrained, quality mesh whose surface is the input's.
// Every input vertex is a node (the first ones, in order). With keep_surface the boundary faces are
// the input faces (no Steiner points on the surface, -Y); without, TetGen splits the input faces
// where the edge length or its quality bounds ask (a CAD export's few large triangles), adding
// points on them: the surface's shape is kept exactly, its triangles follow the edge length.
// Second-order (10-node) tetrahedra on request.

#include "core/names.hpp"
#include "core/progress.hpp"
#include "mesh/surface_mesh.hpp"
#include "mesh/tet_mesh.hpp"

namespace fibermold {

struct TetOptions {
  double edge_length = 0;         ///< m, target; sets TetGen's volume bound a³/(6√2)
  double radius_edge_ratio = 1.5; ///< TetGen's quality bound (-q)
  double min_dihedral_deg = 10;   ///< TetGen's dihedral-angle bound (-q.../angle)
  bool quadratic = false;         ///< 10-node tetrahedra (-o2)
  bool keep_surface = true;       ///< no points added on the surface (-Y)
  double volume_bound_factor = 1; ///< TetGen's volume bound (-a) as a multiple of a³/(6√2)
};

/// What the mesh stage does with the input surface's triangles ([mesh] surface_triangles): keep them
/// exactly (keep), let TetGen split them to the edge length (split), remesh the surface to the edge
/// length (remesh, mesh/surface_remesh.hpp), or choose by their size (auto: surface_treatment).
enum class SurfaceTriangles { automatic, keep, split, remesh };
inline constexpr std::array<Named<SurfaceTriangles>, 4> kSurfaceTrianglesNames{{{SurfaceTriangles::automatic, "auto"},
                                                                                {SurfaceTriangles::keep, "keep"},
                                                                                {SurfaceTriangles::split, "split"},
                                                                                {SurfaceTriangles::remesh, "remesh"}}};
inline std::string_view choice_name(SurfaceTriangles s) { return name_in(kSurfaceTrianglesNames, s); }

/// At "auto": a mean input edge under kCoarsenEdgeFactor × edge_length (a dense scan, even with a
/// few long triangles) makes the stage remesh the surface; else an edge longer than
/// kSplitEdgeFactor × edge_length (a CAD export's few large triangles) makes TetGen split it, unless
/// the input has more vertices than a surface of triangles at the edge length would (a coarse scan
/// with long triangles beside dense ones: split keeps every vertex), which is remeshed; else the
/// triangles are kept. The
/// examples' surfaces, made for their edge lengths, have edges up to 1.63 × theirs and means of
/// 0.79–1.31 × theirs: all kept.
inline constexpr double kSplitEdgeFactor = 2.0;
inline constexpr double kCoarsenEdgeFactor = 0.5;
/// The treatment `policy` asks for `surface` at `edge_length`: keep, split or remesh, never auto.
SurfaceTriangles surface_treatment(SurfaceTriangles policy, const SurfaceMesh& surface, double edge_length);

/// The surface must have passed check_surface(). Throws std::runtime_error when TetGen fails.
TetMesh tetrahedralize(const SurfaceMesh& surface, const TetOptions& options, Progress& progress);

/// Volume of a regular tetrahedron with edge `a`: a³/(6√2).
double regular_tet_volume(double a);

/// The edge length for a body of `volume` when none is asked: about 5,000 regular tets fill it.
double default_edge_length(double volume);

} // namespace fibermold

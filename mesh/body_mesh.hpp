#pragma once
// The body's tet mesh from its checked surface at an edge length: the surface's triangles kept,
// split by TetGen, or remeshed first (surface_treatment decides at "auto"), then attached to the
// input surface, so that what is given on the input reaches the mesh (mesh/surface_places.hpp).
// The mesh is made at the edge length asked: TetGen's volume bound is rescaled until the mean edge
// made is within kEdgeLengthTolerance of it (mesh_body).

#include "core/progress.hpp"
#include "mesh/surface_remesh.hpp"
#include "mesh/tetrahedralize.hpp"

namespace fibermold {

/// The surface TetGen is given, and how it came from the input.
struct MeshedSurface {
  SurfaceTriangles treatment = SurfaceTriangles::keep; ///< keep, split or remesh
  SurfaceMesh surface;                                 ///< the input, or its remeshing
  RemeshReport remeshing;                              ///< when remeshed
};

/// Throws InputError (naming [mesh].edge_length) when remeshing at the edge length leaves an invalid
/// surface: features thinner than the edge length.
MeshedSurface surface_for_mesh(const SurfaceMesh& input, SurfaceTriangles policy, double edge_length);

/// The relative difference between the mean tet edge made and the edge length asked that the mesh
/// stage accepts.
inline constexpr double kEdgeLengthTolerance = 0.15;
/// Once a mesh missed kEdgeLengthTolerance, TetGen reruns until its mean edge is this close to the
/// edge length asked (or five runs).
inline constexpr double kEdgeLengthAim = 0.05;

/// How the mesh was brought to the edge length asked.
struct MeshSizing {
  int tetgen_runs = 0;            ///< TetGen runs, all treatments tried
  double volume_bound_factor = 1; ///< of the mesh kept: TetGen's -a bound over a³/(6√2)
  double mean_edge_length = 0;    ///< m, of the mesh kept
  /// At "auto", the treatment first chosen when its mesh missed the edge length and a remeshed
  /// surface's came closer (its own vertices held the mesh finer than asked); else equal to the
  /// treatment kept.
  SurfaceTriangles first_treatment = SurfaceTriangles::keep;
};

/// About how many tets mesh_body makes of a body of `volume` at `edge_length` with `surface`'s
/// triangles treated as `policy` asks (surface_treatment). Tets fill a body at k per regular tet of
/// the mean edge they come to, ρ × edge_length. Split, ρ = 1 (the volume bound is brought to it)
/// and k = 1.25 (TetGen's own points on the surface); remeshed, ρ = √0.91 (the remeshing's
/// triangles come to a mean edge of about 0.91 × it and hold the boundary there) and k = 1.45;
/// kept, ρ = √(s / edge_length), s the edge of an equilateral triangle of the surface's mean
/// triangle area (the kept triangles hold the boundary at their size, the bound the interior at
/// about edge_length; 1 where that is more than kEdgeLengthTolerance coarse, as the bound is then
/// tightened; remeshed's where it is that fine at "auto", as mesh_body then remeshes), and k = 1.45.
/// Measured (session 25) on the meshes docs/mesh.md lists, of 921 to 1,242,732 tets (boxes split,
/// kept and remeshed, CAD exports, scans, the examples): the tets made are 0.84 to 1.14 × this, but
/// where the input's
/// features or unequal triangles hold the mesh finer than asked: the gripper finger's slots, split,
/// 1.30 ×; fandisk, kept, 1.46 ×.
double expected_tets(double volume, double edge_length, SurfaceTriangles policy, const SurfaceMesh& surface);
inline constexpr double kRemeshedMeanEdge = 0.91; ///< × the edge length: CGAL's isotropic remeshing's mean edge

/// The body's mesh, the surface TetGen was given, and how the mesh was sized.
struct BodyMesh {
  MeshedSurface surface;
  TetMesh mesh;
  MeshSizing sizing;
};

/// The tet mesh of `input` at options.edge_length, attached to `input`. The surface's triangles are
/// treated as `policy` asks (surface_for_mesh). TetGen's volume bound starts at a³/(6√2) × the
/// options' factor; where the mean edge made misses the edge length by more than
/// kEdgeLengthTolerance (split: kEdgeLengthAim), the bound is rescaled and TetGen runs again until
/// the mean edge is within kEdgeLengthAim (at most five runs; the mesh closest to asked is kept);
/// where the surface's triangles are kept, only to refine a mesh coarser than asked. At "auto", a kept or split surface
/// whose own vertices still hold the mesh outside the tolerance is remeshed to the edge length and meshed again, when
/// that comes closer. Throws InputError as surface_for_mesh does, std::runtime_error when TetGen fails.
BodyMesh mesh_body(const SurfaceMesh& input, SurfaceTriangles policy, const TetOptions& options, Progress& progress);

} // namespace fibermold

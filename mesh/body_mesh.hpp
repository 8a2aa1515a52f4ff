#pragma once
// The body's tet mesh from its checked surface at an edge length: the surface's triangles kept,
// split by TetGen, or remeshed first (surface_treatment decides at "auto"), then attached to the
// input surface, so that what is given on the input reaches the mesh (mesh/surface_places.hpp).

#include "core/progress.hpp"
#include "mesh/surface_remesh.hpp"
#include "mesh/tetrahedralize.hpp"

namespace fibermold {

/// The surface TetGen is given, and how it came from the input.
struct MeshedSurface {
  SurfaceTriangles treatment = SurfaceTriangles::keep;  ///< keep, split or remesh
  SurfaceMesh surface;                                  ///< the input, or its remeshing
  RemeshReport remeshing;                               ///< when remeshed
};

/// Throws InputError (naming [mesh].edge_length) when remeshing at the edge length leaves an invalid
/// surface: features thinner than the edge length.
MeshedSurface surface_for_mesh(const SurfaceMesh& input, SurfaceTriangles policy, double edge_length);

/// TetGen on `meshed` (keeping its triangles unless split), attached to `input`. Throws
/// std::runtime_error when TetGen fails.
TetMesh mesh_body(const SurfaceMesh& input, const MeshedSurface& meshed, TetOptions options, Progress& progress);

} // namespace fibermold

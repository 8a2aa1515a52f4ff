#pragma once
// How far a tet mesh's summed volume may lie from the volume its surface encloses, when the tets
// fill that surface: the round-off of two sums of many rounded terms, which grows with their
// number, and the distance of points a mesher added on the surface's triangles.

#include "mesh/surface_mesh.hpp"
#include "mesh/tet_mesh.hpp"

namespace fibermold {

/// A bound (m³) on |Σ tet volumes − signed_volume(surface)| for tets that fill `surface`, their
/// boundary nodes within `deviation` (m) of its triangles. A sum of n terms computed one after
/// another is within (n − 1)·u·Σ|terms| of the exact sum (Higham, Accuracy and Stability of
/// Numerical Algorithms, 2002, eq. 4.4; u = 2⁻⁵³), and each term, a 3 × 3 determinant of rounded
/// differences, carries a few u of its own magnitude: (n + 8)·u·Σ|terms| for each of the two sums.
/// Points within `deviation` of the triangles bound a volume within deviation × area of theirs.
double volume_tolerance(const TetMesh& mesh, const SurfaceMesh& surface, double deviation);

} // namespace fibermold

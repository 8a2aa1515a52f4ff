#pragma once
// Small meshes for the sim tests.

#include "mesh/tetrahedralize.hpp"
#include "primitives.hpp"

namespace fibermold::test {

/// A tetrahedralized box [lo, hi] with edges about `edge`; `quadratic` for 10-node tets.
inline TetMesh box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double edge, bool quadratic = false)
{
  const Eigen::Vector3d size = hi - lo;
  const Eigen::Vector3i cells = (size / edge).array().round().cast<int>().max(1);
  SurfaceMesh surface = box(lo, hi, cells);
  NullProgress progress;
  return tetrahedralize(surface, {edge, 1.5, 10, quadratic}, progress);
}

} // namespace fibermold::test

#pragma once
// Small meshes for the sim tests.

#include "mesh/tetrahedralize.hpp"
#include "primitives.hpp"

namespace fibermold::test {

/// A tetrahedralized box [lo, hi] with edges about `edge`; `quadratic` for 10-node tets.
inline TetMesh box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double edge, bool quadratic = false)
{
  const Eigen::Vector3d size = hi - lo;
  const int n = std::max(1, static_cast<int>(std::round(size.maxCoeff() / edge)));
  SurfaceMesh surface = box(lo, hi, n);
  NullProgress progress;
  return tetrahedralize(surface, {edge, 1.5, 10, quadratic}, progress);
}

} // namespace fibermold::test

#pragma once
// Checking that a surface bounds a solid that can be tetrahedralized: closed, edge- and
// vertex-manifold, consistently oriented with outward normals, free of degenerate faces and of
// self-intersections (CGAL), enclosing a positive volume.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

/// One way in which the surface fails, with a count and one example location.
struct SurfaceProblem {
  std::string message;      ///< "is not closed: 4 border edges"
  Eigen::Vector3d where;    ///< m
  bool repairable = false;  ///< `[mesh] repair = true` can fix it
  std::string repair_scope; ///< what repair fixes of it, where it fixes only some ("fills holes of up to 12 edges")
};

/// A closed void inside the body: a shell that points inward.
struct SurfaceCavity {
  double volume = 0;                                ///< m³
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(); ///< m, of its vertices
};

struct SurfaceCheck {
  std::vector<SurfaceProblem> problems;
  std::vector<SurfaceCavity> cavities; ///< found when the surface is valid
  std::vector<std::string> warnings;
  double volume = 0; ///< m³, signed; meaningful when closed and consistently oriented
  int components = 0;
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero(); ///< m

  bool ok() const { return problems.empty(); }
};

SurfaceCheck check_surface(const SurfaceMesh& surface);

/// Throws InputError with one line per problem, e.g. `surface bar.stl is not closed: 4 border edges,
/// e.g. at (12.0, 3.0, 7.5) mm; set [mesh] repair = true to fix it`.
void require_valid_surface(const SurfaceCheck& check, const SurfaceMesh& surface, bool repaired);

} // namespace fibermold

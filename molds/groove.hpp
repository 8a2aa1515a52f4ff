#pragma once
// Shot 1 of the two-shot casting (paper section VII, Fig. 7): the body with an open groove for each
// muscle, so that the muscle can be laid in from outside before the overmold (shot 2) closes it.
// A groove is the muscle's tube (radius = muscle radius + clearance) swept from the fiber out
// through the skin along the pull direction; it is carved from the body's level set.

#include <vector>

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"
#include "molds/draft.hpp"
#include "molds/voxel_region.hpp"

namespace fibermold {

struct GrooveBody {
  SurfaceMesh mesh;      ///< closed, outward oriented
  double volume = 0;     ///< m³, of the level set
  double adaptivity = 0; ///< what the mesh was made with
};

/// OpenVDB's adaptivity for the groove body's mesh: flat stretches become a few large triangles
/// (the walking robot at 0.1 mm: 132 k triangles instead of 1.17 M, the same volume to 0.01 mL).
constexpr double kGrooveAdaptivity = 0.01;

/// `fibers`: each fiber's centre line as a dense polyline (m). The mesh is adaptive (see
/// LevelSet::mesh) unless that one is not a valid solid (closed, manifold, oriented, without
/// self-intersections): then uniform. With a `draft` the body is grown as Draft says and each
/// groove widens upward by the draft's slope. `solid_body`, when given, receives the (drafted) body
/// before the grooves are cut, meshed the same way: shot 2's cavity.
GrooveBody groove_body(const SurfaceMesh& body, const std::vector<std::vector<Eigen::Vector3d>>& fibers, double radius,
                       const Eigen::Vector3d& pull, double voxel, double adaptivity = kGrooveAdaptivity,
                       const Draft* draft = nullptr, GrooveBody* solid_body = nullptr);

/// What each shot fills, on a grid of `voxel` along pull, from `cavity` (the body, or the drafted
/// body with `taper` = tan(draft)): shot 1 the cavity less the grooves; shot 2 the grooves' space
/// inside the cavity less the muscles laid in them, each resting on its groove's bottom (its axis
/// groove radius − muscle radius below the fiber's).
struct FillRegions {
  VoxelRegion shot1, shot2;
};
FillRegions fill_regions(const SurfaceMesh& cavity, const std::vector<std::vector<Eigen::Vector3d>>& fibers,
                         double radius, double muscle_radius, const Eigen::Vector3d& pull, double voxel,
                         double taper = 0);

/// The fill simulation's voxel: the mold's, or a quarter of the groove's radius when that is
/// coarser (a groove is then still eight voxels across, and the simulation costs a few percent of
/// the mold's making).
double fill_voxel(double voxel, double radius);

} // namespace fibermold

#pragma once
// The design turned into a simulation: held regions, loads and muscles on the mesh, shared by the
// targets stage and `fibermold simulate`.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "design/design.hpp"
#include "mesh/surface_mesh.hpp"
#include "mesh/tet_mesh.hpp"
#include "sim/muscle_energy.hpp"
#include "sim/neo_hookean.hpp"
#include "sim/simulation.hpp"
#include "stages/skin_distance.hpp"

namespace fibermold {

/// A pressurized fiber: its route and its pressure (Pa).
struct Actuation {
  std::string fiber;
  std::vector<Eigen::Vector3d> points, tangents;
  double pressure;
  /// The points are the [[fiber]]'s as the design file draws them (not a target's own, or a route
  /// moved by optimize or collide): a problem with them is placed at their `points`.
  bool as_drawn = false;
};

/// Basis, material, gravity and (when `held`) the [[fixed]] regions as node lists. Throws
/// InputError for a body held nowhere or a region that holds no node.
SimulationOptions simulation_options(const Design& d, const TetMesh& mesh, bool held = true);

/// The mesh nodes a region (box or surface vertices) selects; InputError for a vertex that does not exist.
std::vector<int> region_nodes(const Region& r, const TetMesh& mesh, const Design& d, const std::string& key);

/// What `check` can tell of every region ([[fixed]], loads, poses) from the body's input surface
/// before any mesh exists, refused with the stage's own words: a vertex the surface does not have,
/// a box that misses the body's bounding box (it can hold no node), a point load outside the body.
/// A box that meets the bounding box but catches no node of a coarse mesh is found by the stages.
void require_regions_reach_the_body(const Design& d, const SurfaceMesh& surface);

/// The nodal forces of a `kind = "forces"` target's loads.
Eigen::VectorXd target_forces(const Design& d, const Target& t, const Simulation& sim);

/// "the fiber leaves the body at P", for a fiber's or a tracking curve's `points`, with which of the
/// given points lie outside (`inside` says; counted from 1, as a user counts a TOML array's entries)
/// or, where all lie inside, that the curve bulges out between them; and what to do. For a fiber,
/// `depth` (a point's distance to the skin, m) and `need` (skin_distance) name the points between its
/// ends that lie inside but nearer the skin than a fiber may (a route drawn along the skin, on a
/// notch's floor, leaves the body between its points for that reason, not for a bulge).
std::string leaves_the_body(const std::string& what, const std::vector<Eigen::Vector3d>& points,
                            const Eigen::Vector3d& where, const std::function<bool(const Eigen::Vector3d&)>& inside,
                            const std::function<double(const Eigen::Vector3d&)>& depth = {},
                            const SkinDistance* need = nullptr);

/// The design key of a fiber's or a tracking curve's `points` that leave the body: the one point
/// outside when just one is ("[fiber.m1].points[3]", counted from 1), else the list
/// ("[fiber.m1].points"). `section`: "[fiber.m1]".
std::string points_key(const std::string& section, const std::vector<Eigen::Vector3d>& points,
                       const std::function<bool(const Eigen::Vector3d&)>& inside);

/// The fibers and pressures of a `kind = "fibers"` target.
std::vector<Actuation> target_actuations(const Design& d, const Target& t);

/// Adds one muscle energy per actuation, segmented by [muscle] segments_per_mm; InputError for a
/// fiber that leaves the body. The returned energies are owned by `sim` and keep a reference to
/// `model`, which must outlive them.
std::vector<const MuscleEnergy*> add_muscles(Simulation& sim, const Design& d, const MuscleModel& model,
                                             const std::vector<Actuation>& actuations);

/// How far a result is from converged in the mesh (docs/sim.md, "Discretization error"): the same
/// load solved on a mesh of half the edge length, and the difference of the displacements.
struct Refinement {
  double edge_length = 0;                  ///< m, of the refined mesh
  Eigen::Index nodes = 0, tets = 0;        ///< of the refined mesh
  double surface_max = 0, surface_rms = 0; ///< m, at the input surface's vertices
  double curves_max = 0, curves_rms = 0;   ///< m, at the tracking curves' samples (0 without curves)
  int curve_samples = 0;
  double max_displacement = 0; ///< m, on the refined mesh
};

/// A refinement that moves the surface by more than this share of the largest displacement says the
/// mesh is coarse for the deformation (the examples' muscle-driven rows: 4–17 %; docs/sim.md).
inline constexpr double kCoarseMeshShare = 0.05;

/// The displacements of one load solved on `coarse` (equilibrium `coarse_x`) and on `fine` (a mesh
/// of half the edge length) compared at the input surface's vertices and the tracking curves' samples.
Refinement compare_refined(const Design& d, const Simulation& coarse, const Eigen::VectorXd& coarse_x,
                           const Simulation& fine, const Eigen::VectorXd& fine_x);

/// VTU of the deformed body (points at x(X_i), displacement in mm, von Mises stress in kPa at each
/// tet's centre) with the fibers as deformed polylines.
void write_deformed(const std::filesystem::path& path, const Simulation& sim, const Eigen::VectorXd& x,
                    const std::vector<const MuscleEnergy*>& muscles, const LameParameters& lame);

} // namespace fibermold

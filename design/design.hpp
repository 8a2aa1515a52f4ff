#pragma once
// The design file turned into plain option structs, one per section, in SI units.
// docs/design-file.md documents every key: meaning, unit in the file, default.

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/input_error.hpp"
#include "core/names.hpp"
#include "mesh/tetrahedralize.hpp"
#include "molds/mold_options.hpp"
#include "optimize/bfgs.hpp"
#include "optimize/collision_resolution.hpp"
#include "optimize/routing_optimizer.hpp"
#include "optimize/routing_problem.hpp"
#include "sim/muscle_model.hpp"
#include "sim/simulation.hpp"

namespace fibermold {

using Vec3 = Eigen::Vector3d;

struct DesignOptions {
  std::string name;
  std::filesystem::path surface; ///< absolute
  std::string units = "mm";      ///< units of the surface file: mm | cm | m | in
  double surface_scale = 1e-3;   ///< metres per surface-file unit
};

struct MaterialOptions {
  std::string model = "neo-hookean"; ///< the only one: Neo-Hookean (neo_hookean.hpp)
  /// A silicone of molds/silicone_presets.hpp, whose stiffness and density are the defaults of the keys below and
  /// whose handling README.txt gives; empty: the paper's EcoFlex 00-30 figures (kDefaultSilicone's handling).
  std::string preset;
  double youngs_modulus = SimulationOptions{}.youngs_modulus; ///< Pa
  double poisson_ratio = SimulationOptions{}.poisson_ratio;
  double density = SimulationOptions{}.density; ///< kg/m³
  Vec3 gravity = SimulationOptions{}.gravity;   ///< m/s²
};

struct MeshOptions {
  std::optional<double> edge_length; ///< m; absent: the mesh stage derives it from the body's size
  double radius_edge_ratio = TetOptions{}.radius_edge_ratio; ///< TetGen quality bound
  double min_dihedral_deg = TetOptions{}.min_dihedral_deg;   ///< TetGen quality bound on dihedral angles, degrees
  int max_tets = 2'000'000;                                  ///< refuse to start TetGen on a mesh expected to be larger
  bool repair = false;
  SurfaceTriangles surface_triangles = SurfaceTriangles::automatic;
};

struct SimOptions {
  BasisKind basis = SimulationOptions{}.basis;
  double mls_radius = SimulationOptions{}.mls_radius; ///< × mean edge length
  int quadrature_points = SimulationOptions{}.quadrature_points;
};

/// An axis-aligned box, or a set of surface vertices (0-based indices into the surface file).
struct Region {
  std::optional<std::array<Vec3, 2>> box; ///< min, max in m
  std::vector<int> vertices;
  std::optional<Vec3> point; ///< m; for point loads
};

struct FixedRegion {
  std::string name;
  Region region;
};

struct MuscleOptions {
  MuscleParameters model; ///< diameter and the fitted coefficients (defaults: the paper's)
  double max_pressure = RoutingSettings{}.max_pressure; ///< Pa
  double min_bend_radius =
      kBendRadiusPerDiameter * MuscleParameters{}.diameter;           ///< m (the file's default scales with diameter)
  double segments_per_length = RoutingSettings{}.segments_per_length; ///< segments per m (0.5 per mm)
};

struct Fiber {
  std::string name;
  std::vector<Vec3> points;   ///< m; first and last stay fixed
  std::vector<Vec3> tangents; ///< m; empty: Catmull–Rom tangents from the points
};

struct TrackingCurve {
  std::string name;
  std::vector<Vec3> points; ///< m
  int samples = 40;
  double weight_position = 1.0;
  double weight_orientation = 0.1;
};

struct Load {
  Region region;
  std::optional<Vec3> force;  ///< N, total over the region
  std::optional<Vec3> torque; ///< N·m, about the region's centroid
};

struct FiberActuation {
  std::string name;
  std::vector<Vec3> points; ///< m; empty: the [[fiber]] of that name
  double pressure = 0;      ///< Pa
};

/// A region moved by a rigid motion: turned by `angle` about the line through `about` along
/// `axis`, then moved by `translation`; or, with `curl_from`, turned about its centroid and moved
/// to where a uniform curl from that point takes it.
struct Pose {
  Region region;
  Vec3 axis = Vec3::UnitZ();       ///< unit
  double angle = 0;                ///< rad
  std::optional<Vec3> about;       ///< m; absent: the centroid of the region's nodes
  Vec3 translation = Vec3::Zero(); ///< m
  /// m; the body curls uniformly from here to the region: sets the translation (uniform_curl_translation)
  std::optional<Vec3> curl_from;
};

/// What a target gives (docs/targets.md): loads, a deformed surface, actuated fibers, or regions' poses.
enum class TargetKind { forces, surface, fibers, pose };
inline constexpr std::array<Named<TargetKind>, 4> kTargetKindNames{{{TargetKind::forces, "forces"},
                                                                    {TargetKind::surface, "surface"},
                                                                    {TargetKind::fibers, "fibers"},
                                                                    {TargetKind::pose, "pose"}}};
inline std::string_view choice_name(TargetKind k) { return name_in(kTargetKindNames, k); }

struct Target {
  std::string name;
  TargetKind kind = TargetKind::forces;
  std::vector<Load> loads;            ///< kind = forces
  std::filesystem::path surface;      ///< kind = surface; absolute
  double strain_penalty = 0;          ///< kind = surface; weight of the large-strain penalty
  std::vector<FiberActuation> fibers; ///< kind = fibers
  std::vector<Pose> poses;            ///< kind = pose
  std::vector<std::string> actuators; ///< the [[fiber]]s the optimizer may pressurize for it; empty: all
  double weight = 1;                  ///< multiplies its distance term f_dist in eq. 4
};

struct OptimizeOptions {
  bool enabled = true;
  Strategy strategy = Strategy::simultaneous;
  Method method = MinimizerOptions{}.method;
  int max_iterations = MinimizerOptions{}.max_iterations;
  int route_only_iterations = 0; ///< first, the routes alone at their starting pressures
  int starts = 1; ///< runs: from the first guess and from starts − 1 perturbations of it (perturbed_start.hpp)
  double gradient_tolerance = MinimizerOptions{}.gradient_tolerance;
  double relative_tolerance =
      MinimizerOptions{}.relative_tolerance; ///< over the last MinimizerOptions::window iterations
  double decrease_tolerance = MinimizerOptions{}.decrease_tolerance; ///< Levenberg-Marquardt's convergence
  double weight_curvature = RoutingSettings{}.weight_curvature;
  double weight_skin_barrier = RoutingSettings{}.weight_skin;
  double weight_bend_barrier = RoutingSettings{}.weight_bend;
  double weight_pressure_barrier = RoutingSettings{}.weight_pressure;
  bool refine = false; ///< solve the optimized robot again at half the edge length: its discretization error
};

struct CollideOptions {
  double clearance = ResolutionSettings{}.clearance;   ///< m, between muscle surfaces and to the skin
  double smoothness = ResolutionSettings{}.smoothness; ///< m, the length over which a move spreads along a fiber
  double samples_per_length = 4000;                    ///< centre-line samples per m
  bool reoptimize = false;
};

struct ExportOptions {
  std::vector<std::string> formats{"stl"}; ///< stl | 3mf
  Vec3 printer_volume{0.25, 0.21, 0.21};   ///< m
  double min_wall = 1e-3;                  ///< m, the printer's thinnest reliable wall
};

/// A validated design: every section with defaults filled in, paths absolute, units SI.
struct Design {
  std::filesystem::path file;   ///< the design file, absolute
  std::filesystem::path folder; ///< relative paths resolve against it

  DesignOptions design;
  MaterialOptions material;
  MeshOptions mesh;
  SimOptions sim;
  std::vector<FixedRegion> fixed;
  MuscleOptions muscle;
  std::vector<Fiber> fibers;
  std::vector<TrackingCurve> tracking_curves;
  std::vector<Target> targets;
  OptimizeOptions optimize;
  CollideOptions collide;
  MoldOptions mold;
  ExportOptions export_;

  /// Every key's effective value (defaults included) as written in the design file's units,
  /// e.g. "mold.wall" → "4.0", "fiber.m1.points" → "[[0, 0, 0], ...]". The runner hashes these to
  /// decide which stages are stale and names the key that changed.
  std::map<std::string, std::string> values;
  /// Where each key given was written: "[mold].voxel" → {line, column}, and each point of a list of
  /// points: "[fiber.m1].points[2]" (counted from 1); a key left at its default is absent.
  std::map<std::string, std::pair<int, int>> places;
};

/// A problem with `key` of the design (e.g. "[mold].voxel", "[fiber.m1]"), found after reading
/// it: at the key's line when it was written, else at the file.
Diagnostic design_problem(const Design& d, const std::string& key, std::string message);

} // namespace fibermold

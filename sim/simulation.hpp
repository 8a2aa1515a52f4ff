#pragma once
// A body ready to simulate: its basis, quadrature points, and total potential energy
// E = E_elast + E_gravity + E_dirichlet (+ loads and muscles added by the caller), minimized by Newton.

#include <memory>
#include <string>
#include <vector>

#include "core/names.hpp"
#include "mesh/tet_mesh.hpp"
#include "sim/newton_solver.hpp"
#include "sim/quadrature_points.hpp"
#include "sim/shape_functions.hpp"
#include "sim/soft_dirichlet.hpp"

namespace fibermold {

/// The shape functions (paper section IV): MLS of linear or quadratic completeness, or FEM.
enum class BasisKind { mls_linear, mls_quadratic, fem_p1, fem_p2 };
inline constexpr std::array<Named<BasisKind>, 4> kBasisNames{{{BasisKind::mls_linear, "mls-linear"},
                                                              {BasisKind::mls_quadratic, "mls-quadratic"},
                                                              {BasisKind::fem_p1, "fem-p1"},
                                                              {BasisKind::fem_p2, "fem-p2"}}};
inline std::string_view choice_name(BasisKind b) { return name_in(kBasisNames, b); }

struct SimulationOptions {
  BasisKind basis = BasisKind::mls_linear;
  double mls_radius = 1.7; ///< × mean edge length
  int quadrature_points = 8;
  double youngs_modulus = 86.4e3; ///< Pa
  double poisson_ratio = 0.47;
  double density = 1070; ///< kg/m³
  Eigen::Vector3d gravity{0, 0, -9.81};
  double dirichlet_penalty = 1e4;                           ///< k = penalty × E × mean edge length
  std::vector<std::vector<int>> fixed_nodes;                ///< held nodes, one list per region
  std::vector<std::pair<int, Eigen::Vector3d>> moved_nodes; ///< nodes held at a given position (m)
  NewtonOptions newton;
};

class Simulation {
public:
  /// Throws std::invalid_argument for a fixed region that holds no node or a body held nowhere.
  Simulation(const TetMesh& mesh, SimulationOptions options);

  /// The Newton settings of every later solve.
  NewtonOptions& newton_options() { return options_.newton; }
  ~Simulation();

  const TetMesh& mesh() const { return mesh_; }
  const Basis& basis() const { return *basis_; }
  const QuadraturePoints& quadrature_points() const { return qp_; }
  const Eigen::VectorXd& masses() const { return masses_; }
  /// Positive nodal volumes, for spreading loads (external_forces.hpp).
  Eigen::VectorXd load_weights() const;
  double mean_edge_length() const { return mean_edge_; }
  Eigen::VectorXd rest() const;

  /// Adds a term (a load, a muscle) to the total energy; call before the first solve.
  void add_energy(std::unique_ptr<Energy> energy);
  /// Replaces the terms set by the last call (none at first), at any time: muscles whose routes
  /// or pressures change between solves, as in optimization.
  void set_variable_energies(std::vector<std::unique_ptr<Energy>> energies);

  /// Later calls use Newton solver `slot` (0, 1, …; made on first use). Each keeps its own
  /// variable terms and factorization, so that solves alternating between loads (the optimizer's
  /// targets) each start on the factorization their own last solve ended with.
  void use_solver(int slot);
  /// Moves the nodes of SimulationOptions::moved_nodes (same order) to `positions` (m) for the
  /// next solves, keeping every factorization: a target reached in steps.
  void move_nodes(const std::vector<Eigen::Vector3d>& positions);
  /// Equilibrium from x (warm start), in place.
  NewtonSummary solve(Eigen::VectorXd& x, Progress& progress);
  NewtonSolver& solver();
  /// Symbolic analyses of all the solvers so far.
  int symbolic_analyses() const;

  /// Deformed position of each node's rest position: x(X_i) = Σ_j N_j(X_i) x_j (MLS approximates).
  Eigen::MatrixX3d deformed_nodes(const Eigen::VectorXd& x) const;

private:
  const TetMesh& mesh_;
  SimulationOptions options_;
  double mean_edge_ = 0;
  std::unique_ptr<Basis> basis_;
  QuadraturePoints qp_;
  Eigen::VectorXd masses_;
  std::vector<std::unique_ptr<Energy>> energies_;
  std::vector<std::vector<std::unique_ptr<Energy>>> variable_energies_; ///< per solver
  std::vector<std::unique_ptr<NewtonSolver>> solvers_;
  std::size_t slot_ = 0;
  std::vector<ShapeEval> at_nodes_;
  SoftDirichlet* dirichlet_ = nullptr;
  std::size_t fixed_points_ = 0; ///< the held points before the moved ones in dirichlet_
};

} // namespace fibermold

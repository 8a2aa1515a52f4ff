#pragma once
// Equilibrium (paper eq. 3) by Newton's method: PSD-projected Hessian, CHOLMOD with the symbolic
// analysis reused, a backtracking line search that never accepts an invalid (inverted) state, and
// convergence on the gradient norm relative to the force scale. Warm-starts from the given x.

#include <string>
#include <vector>

#include "core/progress.hpp"
#include "sim/cholmod_solver.hpp"
#include "sim/energy.hpp"

namespace fibermold {

struct NewtonOptions {
  int max_iterations = 100;
  double tolerance = 1e-8;  ///< converged when |∇E| ≤ tolerance × force_scale
  double force_scale = 1.0; ///< N
  int max_halvings = 40;
  /// Steps on a kept factorization K are L-BFGS steps from the pairs of this many of the last
  /// steps, with K⁻¹ as the initial inverse Hessian (lbfgs_correction.hpp). K is then kept while
  /// each step is taken with at most one halving. 0: plain steps on K, kept by reuse_contraction.
  int quasi_newton_pairs = 8;
  /// Without quasi-Newton pairs, a full step that shrank |∇E| by at least this factor lets the next
  /// step reuse its factorization; 0 (with quasi_newton_pairs = 0) refactorizes at every step
  /// (plain Newton). With pairs, it applies below the tolerance only.
  double reuse_contraction = 0.5;
  /// The solve ends on a fresh factorization taken within 1e3 × the tolerance (at once when |∇E|
  /// gets there, or when a reused factorization reaches the tolerance), 100× below the tolerance
  /// or where steps on it stop shrinking |∇E| (round-off): objective values compared by a line
  /// search then do not carry the tolerance's noise, and where that factorization is of the exact
  /// Hessian, solve_with_hessian at that state uses it.
  bool finish_on_fresh_step = false;
};

/// What a solve did. Non-convergence is a status with the residual, never a result to use.
struct NewtonSummary {
  bool converged = false;
  int iterations = 0;
  double residual = 0; ///< |∇E| at the end, N
  double initial_residual = 0;
  double energy = 0; ///< J
  double seconds_assembly = 0, seconds_factorization = 0, seconds_solve = 0, seconds_total = 0;
  int assemblies = 0, factorizations = 0;
  int products = 0;    ///< Hessian products of its exact Newton steps' conjugate gradients
  std::string message; ///< why it stopped

  std::string brief() const;
};

/// What many solves did together (the optimizer's cost account).
struct NewtonTotals {
  int solves = 0, iterations = 0, assemblies = 0, factorizations = 0, products = 0;
  double seconds_assembly = 0, seconds_factorization = 0;

  NewtonTotals& operator+=(const NewtonSummary& s);
};

class NewtonSolver {
public:
  /// The energies must outlive the solver. Builds the Hessian pattern from their stencils.
  /// `keep_pattern`: the variable energies' pairs outside that pattern are lumped onto the
  /// diagonal (SparseHessian::add_coupling) instead of growing it, so that CHOLMOD's symbolic
  /// analysis is done once however the muscles move (for MLS bases, whose far pairs are the
  /// small products of shape functions near the edges of their supports). Newton converges on
  /// the exact gradient all the same; the adjoint solve refines with the exact Hessian's products
  /// (conjugate gradients preconditioned by the lumped factorization) and, where that does not
  /// converge, grows the pattern then (a second analysis).
  NewtonSolver(std::vector<const Energy*> energies, Eigen::Index num_nodes, bool keep_pattern = false);

  /// Replaces the energies given by the last call (none at first) and keeps the others: the
  /// muscles, whose stencils move with their routes during optimization. Without keep_pattern
  /// the Hessian pattern grows to fit them; while it already does, CHOLMOD's symbolic analysis is
  /// kept.
  void set_variable_energies(const std::vector<const Energy*>& energies);
  /// Symbolic analyses so far (one per pattern).
  int analyses() const { return cholmod_.analyses(); }

  Eigen::VectorXd gradient(const Eigen::VectorXd& x) const;
  /// E(x) with g = ∇E(x) in one pass, or +∞ where x is invalid.
  double value_and_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const;
  /// Assembles the (projected) Hessian at x.
  const SparseHessian& hessian(const Eigen::VectorXd& x, bool project = true);

  /// Minimizes from x (updated in place).
  NewtonSummary solve(Eigen::VectorXd& x, const NewtonOptions& options, Progress& progress);

  /// Solves H(x) λ = b with the exact Hessian at x (an equilibrium, where it is positive definite):
  /// the adjoint solve of eq. 9. Returns false when H(x) is not positive definite (its
  /// factorization fails, or conjugate gradients meet a direction of non-positive curvature). At the state the
  /// last solve ended on, when its factorization is of the exact Hessian at a state near the
  /// tolerance (so with finish_on_fresh_step where the Hessian there is definite), that
  /// factorization preconditions conjugate gradients with H(x)λ from differences of ∇E: no assembly.
  bool solve_with_hessian(const Eigen::VectorXd& x, const Eigen::VectorXd& b, Eigen::VectorXd& lambda);
  /// K⁻¹B with the factorization K held after solve_with_hessian(x, …): of the Hessian at x or a few
  /// steps before it, or with lumped pairs (keep_pattern), so an approximation of H(x)⁻¹B, not
  /// refined (what a model needs: the Gauss-Newton Hessian's sensitivities). False when no
  /// factorization is held.
  bool solve_with_factorization(const Eigen::MatrixXd& B, Eigen::MatrixXd& X) const;

private:
  enum class Factorization { none, exact, shifted, projected };

  /// Assembles and factorizes the Hessian at x: exact, else exact + τI, else projected (and
  /// shifted until it factorizes); only projected when !exact_first. none with s.message set
  /// when it cannot.
  Factorization factorize_at(const Eigen::VectorXd& x, NewtonSummary& s, double& shift, bool exact_first);
  /// Factorizes the assembled exact Hessian + τI for the first τ tried that makes it positive
  /// definite (τ in shift); false when none up to a limit does.
  bool factorize_shifted(NewtonSummary& s, double& shift);
  /// The adjoint solve by conjugate gradients on the exact Hessian's products, preconditioned by the
  /// factorization held (the last solve's, or of the Hessian at x with lumped pairs); false when it
  /// does not converge in `max_products` products (`products`: how many it took).
  bool conjugate_gradient_solve(const Eigen::VectorXd& x, const Eigen::VectorXd& b, Eigen::VectorXd& lambda,
                                int max_products, int& products) const;

  // The steps of solve(), a state machine over SolveState (newton_solver.cpp): each says whether
  // the solve goes on.
  struct SolveState;
  struct Trial;
  /// The step from st.x: exact Newton near the tolerance where pairs are lumped, else quasi-Newton.
  Eigen::VectorXd step(SolveState& st) const;
  void converge(SolveState& st, bool factorization_serves_adjoint);
  bool stops_before_step(SolveState& st);
  bool refactorizes_if_stale(SolveState& st);
  Trial line_search(SolveState& st, const Eigen::VectorXd& dx);
  bool retries_after_failed_search(SolveState& st);
  bool stops_at_step(SolveState& st, const Trial& t);
  void take_step(SolveState& st, Trial& t);

  std::vector<const Energy*> energies_;
  std::size_t fixed_energies_;
  SparseHessian hessian_;
  bool keep_pattern_;
  std::vector<std::vector<int>> variable_stencils_;
  CholmodSolver cholmod_;
  Factorization kind_ = Factorization::none; ///< what cholmod_ holds
  double last_shift_ = 0;      ///< the last τ that served (in any solve): a search starts at a quarter of it
  bool adjoint_ready_ = false; ///< solve_with_hessian(adjoint_x_) may use the factorization
  Eigen::VectorXd adjoint_x_;
  bool restart_ready_ = false; ///< a solve from restart_x_ may begin on the factorization
  Eigen::VectorXd restart_x_;
};

} // namespace fibermold

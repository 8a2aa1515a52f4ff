#include "sim/newton_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "sim/lbfgs_correction.hpp"

namespace fibermold {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// |∇E| within this factor of the tolerance: steps on the exact Hessian there converge.
constexpr double kNearTolerance = 1e3;
/// Where a solve that finishes on a fresh factorization ends, relative to the tolerance.
constexpr double kFarBelow = 1e-2;
/// The round-off floor of |∇E|: a step on a fresh factorization of the exact Hessian that had to
/// shrink below kRoundOffStep finds no lower |∇E| in double precision. Within kRoundOffAccept of the
/// tolerance that is convergence. The tolerance scales with the silicone (E h²), and a stiff
/// passive muscle in it can put the floor above it: the walking robot's twist at 0.1 kPa stopped at
/// 6.4e-8 N against 1.8e-8 N for 100 iterations under OpenBLAS's Sandybridge kernels, and converged
/// in 4 under the others (session 17).
constexpr double kRoundOffStep = 1e-6, kRoundOffAccept = 1e2;
/// Steps on one factorization at most.
constexpr int kLongestReuse = 50;
/// A solve takes at most max_iterations steps on fresh factorizations and this many times
/// max_iterations steps in all (from rest the examples take at most 155).
constexpr int kStepsPerIteration = 10;

SparseHessian make_pattern(const std::vector<const Energy*>& energies, Eigen::Index n)
{
  std::vector<std::vector<int>> stencils;
  for (const Energy* e : energies) e->stencils(stencils);
  return SparseHessian(n, stencils);
}
} // namespace

std::string NewtonSummary::brief() const
{
  return fmt::format("{} after {} iterations: |∇E| = {:.3e} N (from {:.3e}), {:.3f} s", converged ? "converged" : "NOT converged",
                     iterations, residual, initial_residual, seconds_total);
}

NewtonTotals& NewtonTotals::operator+=(const NewtonSummary& s)
{
  ++solves;
  iterations += s.iterations;
  assemblies += s.assemblies;
  factorizations += s.factorizations;
  seconds_assembly += s.seconds_assembly;
  seconds_factorization += s.seconds_factorization;
  return *this;
}

NewtonSolver::NewtonSolver(std::vector<const Energy*> energies, Eigen::Index num_nodes)
    : energies_(std::move(energies)), fixed_energies_(energies_.size()), hessian_(make_pattern(energies_, num_nodes))
{
}

void NewtonSolver::set_variable_energies(const std::vector<const Energy*>& energies)
{
  adjoint_ready_ = false;
  energies_.resize(fixed_energies_);
  energies_.insert(energies_.end(), energies.begin(), energies.end());
  std::vector<std::vector<int>> stencils;
  for (const Energy* e : energies) e->stencils(stencils);
  if (!hessian_.contains(stencils)) hessian_ = SparseHessian(hessian_, stencils);
}

Eigen::VectorXd NewtonSolver::gradient(const Eigen::VectorXd& x) const
{
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  for (const Energy* term : energies_) term->add_gradient(x, g);
  return g;
}

const SparseHessian& NewtonSolver::hessian(const Eigen::VectorXd& x, bool project)
{
  hessian_.set_zero();
  for (const Energy* term : energies_) term->add_hessian(x, hessian_, project);
  return hessian_;
}

double NewtonSolver::value_and_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const
{
  g.setZero(x.size());
  double e = 0;
  for (const Energy* term : energies_)
    if (!((e += term->value_and_gradient(x, g)) < HUGE_VAL)) return HUGE_VAL;
  return e;
}

bool NewtonSolver::solve_with_hessian(const Eigen::VectorXd& x, const Eigen::VectorXd& b, Eigen::VectorXd& lambda)
{
  if (adjoint_ready_ && x.size() == adjoint_x_.size() && x == adjoint_x_ && refined_solve(x, b, lambda)) return true;
  adjoint_ready_ = false;
  hessian(x, false);
  kind_ = cholmod_.factorize(hessian_.matrix(), 0) ? Factorization::exact : Factorization::none;
  if (kind_ != Factorization::exact) {
    restart_ready_ = false;
    return false;
  }
  lambda = cholmod_.solve(b);
  return lambda.allFinite();
}

bool NewtonSolver::refined_solve(const Eigen::VectorXd& x, const Eigen::VectorXd& b, Eigen::VectorXd& lambda) const
{
  // The factorization K is of the exact Hessian a few steps before x, at a state within
  // kNearTolerance of the tolerance. Iterative refinement, with H(x)λ from central
  // differences of ∇E over a displacement of 1e-6 of the body's extent, takes λ from K⁻¹b
  // (relative error 3e-7 on the test's bar) to H(x)⁻¹b (8e-10 after one step). The corrections
  // shrink by the rate ρ = |I − K⁻¹H(x)| (the first one's size estimates it), so what remains after
  // one of size s is about ρ s: done below 1e-8. A rate above 0.1 means K is too far from H(x) (or
  // H(x) is not definite): the caller then factorizes H(x) itself.
  lambda = cholmod_.solve(b);
  const auto nodes = x.reshaped(3, x.size() / 3);
  const double extent = (nodes.rowwise().maxCoeff() - nodes.rowwise().minCoeff()).maxCoeff();
  double last = 0;
  for (int step = 0; step < 4; ++step) {
    const double h = 1e-6 * extent / lambda.cwiseAbs().maxCoeff();
    if (!(std::isfinite(h) && h > 0)) return false;
    const Eigen::VectorXd Hlambda = (gradient(x + h * lambda) - gradient(x - h * lambda)) / (2 * h);
    if (!(lambda.dot(Hlambda) > 0)) return false;
    const Eigen::VectorXd correction = cholmod_.solve(b - Hlambda);
    const double size = correction.norm() / lambda.norm();
    const double rate = step == 0 ? size : size / last;
    if (!(rate <= 0.1)) return false;
    lambda += correction;
    if (rate * size <= 1e-8) return lambda.allFinite();
    last = size;
  }
  return false;
}

NewtonSolver::Factorization NewtonSolver::factorize_at(const Eigen::VectorXd& x, NewtonSummary& s, double& shift, bool exact_first)
{
  // The exact Hessian where it is positive definite (quadratic convergence near a stable
  // equilibrium); shifted by τI where it is indefinite but only softly (a state passing a snap or
  // a buckling mode); the per-point PSD projection where it is far from definite.
  shift = 0;
  if (exact_first) {
    auto t = Clock::now();
    hessian(x, false);
    s.seconds_assembly += since(t);
    ++s.assemblies;
    t = Clock::now();
    ++s.factorizations;
    Factorization kind = cholmod_.factorize(hessian_.matrix(), 0) ? Factorization::exact
                         : factorize_shifted(s, shift)               ? Factorization::shifted
                                                                     : Factorization::none;
    s.seconds_factorization += since(t);
    if (kind != Factorization::none) return kind;
  }
  auto t = Clock::now();
  hessian(x, true);
  s.seconds_assembly += since(t);
  ++s.assemblies;
  // A PSD-projected Hessian can be singular (e.g. at rest with no load); shift until it factorizes.
  t = Clock::now();
  const double diagonal = hessian_.matrix().diagonal().cwiseAbs().maxCoeff();
  if (!(diagonal > 0 && std::isfinite(diagonal))) {
    s.message = "the Hessian is zero or not finite";
    return Factorization::none;
  }
  bool factorized = false;
  shift = 0;
  while (!factorized && shift <= diagonal) {  // at most 11 attempts
    factorized = cholmod_.factorize(hessian_.matrix(), shift);
    ++s.factorizations;
    if (!factorized) shift = shift == 0 ? 1e-10 * diagonal : shift * 10;
  }
  s.seconds_factorization += since(t);
  if (!factorized) s.message = "the Hessian is singular: is the body held (a [[fixed]] region)?";
  return factorized ? Factorization::projected : Factorization::none;
}

bool NewtonSolver::factorize_shifted(NewtonSummary& s, double& shift)
{
  // H + τI for the first τ of τ₀·4ᵏ that is positive definite, τ₀ a small fraction of the largest
  // diagonal entry or a quarter of the last τ that served, in this solve or an earlier one (so τ
  // shrinks 4× per search that succeeds at once); a multiple of the identity added until Cholesky
  // succeeds: Nocedal & Wright, Numerical Optimization, Algorithm 3.3, with 4× steps. Starting
  // each solve's search from the smallest τ cost the walking robot's coarse optimization 505
  // factorizations where this takes 394.
  // Along a soft mode of slightly negative curvature (stiff terms that nearly cancel) the step
  // then follows the mode; the per-point projection drops the negative part, makes the mode as
  // stiff as the elements, and Newton crawls: on the walking robot 40 to 100 full steps, each
  // lowering |∇E| by at most 4 %. Beyond kLargestShift the projection is the better model.
  constexpr double kSmallestShift = 1e-8, kLargestShift = 1e-2;
  const double diagonal = hessian_.matrix().diagonal().cwiseAbs().maxCoeff();
  if (!(diagonal > 0 && std::isfinite(diagonal))) return false;
  for (shift = std::max(kSmallestShift * diagonal, last_shift_ / 4); shift <= kLargestShift * diagonal; shift *= 4) {
    ++s.factorizations;
    if (cholmod_.factorize(hessian_.matrix(), shift)) {
      last_shift_ = shift;
      return true;
    }
  }
  last_shift_ = 0;
  return false;
}

NewtonSummary NewtonSolver::solve(Eigen::VectorXd& x, const NewtonOptions& options, Progress& progress)
{
  const auto start = Clock::now();
  NewtonSummary s;
  adjoint_ready_ = false;
  Eigen::VectorXd g;
  double E = value_and_gradient(x, g);
  if (!(E < HUGE_VAL)) {
    s.message = "the starting state is invalid (an inverted element)";
    return s;
  }
  s.initial_residual = g.norm();
  const double goal = options.tolerance * options.force_scale;
  double last_alpha = 0, shift = 0;
  // A solve that starts where the last one ended (the optimizer's warm start, with the muscles
  // moved a little) takes its first step on that solve's factorization of the exact Hessian: a
  // design step that changes little then costs no assembly before the finishing one.
  bool fresh = false;          // the factorization is of the Hessian at x
  bool stale = !(restart_ready_ && x.size() == restart_x_.size() && x == restart_x_);
  restart_ready_ = false;
  bool exact_first = true;     // false: the next factorization is the projected Hessian
  bool near = false;           // the factorization is of the Hessian at a state within kNearTolerance
  bool finishing = false;      // below the tolerance, taking the step that finish_on_fresh_step asks for
  int full_steps = 0;  // steps on a fresh factorization: what max_iterations bounds
  int reused_run = 0;
  LbfgsCorrection secant(options.quasi_newton_pairs);  // the steps since the last factorization
  const auto converge = [&](bool factorization_serves_adjoint) {
    s.converged = true;
    s.message = "gradient below tolerance";
    adjoint_ready_ = factorization_serves_adjoint;
    if (adjoint_ready_) adjoint_x_ = x;
    restart_ready_ = kind_ == Factorization::exact;
    restart_x_ = x;
  };
  for (;;) {
    s.residual = g.norm();
    s.energy = E;
    if (!std::isfinite(s.residual)) {
      s.message = "the gradient is not finite";
      break;
    }
    // A solve that must end on a fresh factorization takes it near the tolerance, where steps on it
    // contract by 1e-2 or more, and ends far below the tolerance (or where its steps stop shrinking
    // |∇E|: round-off); reused ones from farther only approach it.
    if (s.residual <= goal) {
      if (!options.finish_on_fresh_step || (near && (s.residual <= kFarBelow * goal || stale))) {
        converge(near && kind_ == Factorization::exact);
        break;
      }
      if (!near) {
        finishing = true;
        stale = true;
      }
    }
    if (options.finish_on_fresh_step && !fresh && !near && s.residual <= kNearTolerance * goal) stale = true;
    if ((full_steps >= options.max_iterations || s.iterations >= kStepsPerIteration * options.max_iterations) && !finishing) {
      if (s.residual <= goal) converge(near && kind_ == Factorization::exact);
      else s.message = fmt::format("no convergence in {} iterations ({} steps)", options.max_iterations, s.iterations);
      break;
    }
    if (stale) {
      kind_ = factorize_at(x, s, shift, exact_first);
      if (kind_ == Factorization::none) {
        if (finishing) converge(false);  // x is below the tolerance all the same
        break;
      }
      stale = false;
      reused_run = 0;
      fresh = true;
      exact_first = true;
      near = s.residual <= kNearTolerance * goal;
    }
    progress.checkpoint(-1, fmt::format("Newton iteration {}: |∇E| = {:.3e} N, last step {:.3g}, shift {:.3g}{}", s.iterations,
                                        s.residual, last_alpha, shift, fresh ? "" : ", Hessian reused"));
    auto t = Clock::now();
    if (fresh) secant.clear();
    const Eigen::VectorXd dx = -secant.apply(g, [&](const Eigen::VectorXd& q) { return cholmod_.solve(q); });
    s.seconds_solve += since(t);

    // Backtracking (Armijo) that rejects any invalid state.
    const double slope = g.dot(dx);
    double alpha = 1;
    Eigen::VectorXd trial, trial_g;
    double trial_E = HUGE_VAL;
    int halvings = 0;
    // A kept factorization whose step needs more than a few halvings is refactorized instead.
    const int max_halvings = fresh ? options.max_halvings : std::min(options.max_halvings, 4);
    for (; slope < 0 && halvings <= max_halvings; ++halvings, alpha /= 2) {
      trial = x + alpha * dx;
      trial_E = value_and_gradient(trial, trial_g);
      if (!(trial_E < HUGE_VAL)) continue;
      if (trial_E <= E + 1e-4 * alpha * slope) break;
      // Near the minimum the energy difference drowns in round-off: accept a step that lowers |∇E|.
      if (std::abs(trial_E - E) <= 1e-12 * std::abs(E) && trial_g.norm() < s.residual) break;
    }
    if (!(slope < 0) || halvings > max_halvings) {
      if (!fresh || kind_ == Factorization::shifted) {  // an old Hessian's direction: refactorize
        stale = true;                                    // and try again; a shifted one's: project
        exact_first = !fresh;
        continue;
      }
      if (s.residual <= goal) {  // the factorization is of the Hessian at x, which is below the tolerance
        converge(kind_ == Factorization::exact);
        break;
      }
      s.message = "the line search found no decrease";
      break;
    }
    if (fresh && kind_ == Factorization::exact && alpha < kRoundOffStep && s.residual <= kRoundOffAccept * goal) {
      converge(true);  // the factorization is of the exact Hessian at x
      s.message = fmt::format("gradient at its round-off floor, {:.2g}× the tolerance", s.residual / goal);
      break;
    }
    if (finishing && !(trial_g.norm() <= goal)) {  // the extra step must not undo convergence
      converge(false);
      break;
    }
    secant.add(trial - x, trial_g - g);
    x = std::move(trial);
    E = trial_E;
    g = std::move(trial_g);
    last_alpha = alpha;
    ++s.iterations;
    if (fresh) ++full_steps;
    finishing = false;
    // The factorization is kept for the next step while its steps go well: a step then costs a
    // gradient and a solve instead of an assembly and a factorization. Quasi-Newton: while a step
    // needs at most one halving, unless the factorization is of a shifted Hessian (a poor model:
    // kept, a bent muscle bar crawled 21 steps at α = 0.5 on one; a projected one is kept, and
    // its steps are corrected by the pairs like any other). Plain: while full steps halve |∇E|.
    // From rest, sim_bench's twisting bar at 2,433 DoFs took 16 factorizations in 29 steps with
    // plain reuse, 10 in 39 when only full quasi-Newton steps kept it, 5 in 57 with this rule.
    // Below the tolerance a kept factorization must still halve |∇E|: where it stops doing so
    // (round-off), a solve that finishes on a fresh factorization ends there.
    const bool contracted = g.norm() <= options.reuse_contraction * s.residual;
    stale = options.quasi_newton_pairs > 0
                ? !(alpha >= 0.5 && kind_ != Factorization::shifted && (s.residual > goal || contracted))
                : !(alpha == 1 && contracted);
    reused_run = stale ? 0 : reused_run + 1;
    if (reused_run > kLongestReuse) stale = true;
    fresh = false;
  }
  s.seconds_total = since(start);
  return s;
}

} // namespace fibermold

#include "sim/newton_solver.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>

namespace fibermold {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

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

NewtonSolver::NewtonSolver(std::vector<const Energy*> energies, Eigen::Index num_nodes)
    : energies_(std::move(energies)), fixed_energies_(energies_.size()), hessian_(make_pattern(energies_, num_nodes))
{
}

void NewtonSolver::set_variable_energies(const std::vector<const Energy*>& energies)
{
  energies_.resize(fixed_energies_);
  energies_.insert(energies_.end(), energies.begin(), energies.end());
  std::vector<std::vector<int>> stencils;
  for (const Energy* e : energies) e->stencils(stencils);
  if (!hessian_.contains(stencils)) hessian_ = SparseHessian(hessian_, stencils);
}

double NewtonSolver::energy(const Eigen::VectorXd& x) const
{
  double e = 0;
  for (const Energy* term : energies_) e += term->value(x);
  return e;
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

bool NewtonSolver::is_valid(const Eigen::VectorXd& x) const
{
  for (const Energy* term : energies_)
    if (!term->is_step_valid(x)) return false;
  return true;
}

bool NewtonSolver::solve_with_hessian(const Eigen::VectorXd& x, const Eigen::VectorXd& b, Eigen::VectorXd& lambda)
{
  hessian(x, false);
  if (!cholmod_.factorize(hessian_.matrix(), 0)) return false;
  lambda = cholmod_.solve(b);
  return lambda.allFinite();
}

bool NewtonSolver::factorize_at(const Eigen::VectorXd& x, NewtonSummary& s, double& shift)
{
  // The exact Hessian where it is positive definite (quadratic convergence near a stable
  // equilibrium); the per-point PSD projection where it is not.
  auto t = Clock::now();
  hessian(x, false);
  s.seconds_assembly += since(t);
  ++s.assemblies;
  t = Clock::now();
  shift = 0;
  bool factorized = cholmod_.factorize(hessian_.matrix(), 0);
  ++s.factorizations;
  s.seconds_factorization += since(t);
  if (factorized) return true;
  t = Clock::now();
  hessian(x, true);
  s.seconds_assembly += since(t);
  ++s.assemblies;
  // A PSD-projected Hessian can be singular (e.g. at rest with no load); shift until it factorizes.
  t = Clock::now();
  const double diagonal = hessian_.matrix().diagonal().cwiseAbs().maxCoeff();
  if (!(diagonal > 0 && std::isfinite(diagonal))) {
    s.message = "the Hessian is zero or not finite";
    return false;
  }
  while (!factorized && shift <= diagonal) {  // at most 11 attempts
    factorized = cholmod_.factorize(hessian_.matrix(), shift);
    ++s.factorizations;
    if (!factorized) shift = shift == 0 ? 1e-10 * diagonal : shift * 10;
  }
  s.seconds_factorization += since(t);
  if (!factorized) s.message = "the Hessian is singular: is the body held (a [[fixed]] region)?";
  return factorized;
}

NewtonSummary NewtonSolver::solve(Eigen::VectorXd& x, const NewtonOptions& options, Progress& progress)
{
  const auto start = Clock::now();
  NewtonSummary s;
  if (!is_valid(x)) {
    s.message = "the starting state is invalid (an inverted element)";
    return s;
  }
  double E = energy(x);
  Eigen::VectorXd g = gradient(x);
  s.initial_residual = g.norm();
  const double goal = options.tolerance * options.force_scale;
  double last_alpha = 0, shift = 0;
  bool fresh = false;  // the factorization is of the Hessian at x
  bool stale = true;   // the factorization must be redone before the next step
  int full_steps = 0;  // steps on a fresh factorization: what max_iterations bounds (a reused step
                       // must halve |∇E|, so at most about log2(|∇E₀| / goal) of them come in a row)
  for (;;) {
    s.residual = g.norm();
    s.energy = E;
    if (!std::isfinite(s.residual)) {
      s.message = "the gradient is not finite";
      break;
    }
    if (s.residual <= goal) {
      s.converged = true;
      s.message = "gradient below tolerance";
      break;
    }
    if (full_steps == options.max_iterations) {
      s.message = fmt::format("no convergence in {} iterations", options.max_iterations);
      break;
    }
    if (stale) {
      if (!factorize_at(x, s, shift)) break;
      stale = false;
      fresh = true;
    }
    progress.checkpoint(-1, fmt::format("Newton iteration {}: |∇E| = {:.3e} N, last step {:.3g}, shift {:.3g}{}", s.iterations,
                                        s.residual, last_alpha, shift, fresh ? "" : ", Hessian reused"));
    auto t = Clock::now();
    const Eigen::VectorXd dx = -cholmod_.solve(g);
    s.seconds_solve += since(t);

    // Backtracking (Armijo) that rejects any invalid state.
    const double slope = g.dot(dx);
    double alpha = 1;
    Eigen::VectorXd trial;
    double trial_E = HUGE_VAL;
    int halvings = 0;
    for (; slope < 0 && halvings <= options.max_halvings; ++halvings, alpha /= 2) {
      trial = x + alpha * dx;
      if (!is_valid(trial)) continue;
      trial_E = energy(trial);
      if (trial_E <= E + 1e-4 * alpha * slope) break;
      // Near the minimum the energy difference drowns in round-off: accept a step that lowers |∇E|.
      if (std::abs(trial_E - E) <= 1e-12 * std::abs(E) && gradient(trial).norm() < s.residual) break;
    }
    if (!(slope < 0) || halvings > options.max_halvings) {
      if (!fresh) {  // an old Hessian's direction: refactorize here and try again
        stale = true;
        continue;
      }
      s.message = "the line search found no decrease";
      break;
    }
    x = trial;
    E = trial_E;
    last_alpha = alpha;
    g = gradient(x);
    ++s.iterations;
    if (fresh) ++full_steps;
    // The factorization is kept for the next step while the gradient keeps shrinking fast: a step
    // then costs a gradient and a solve instead of an assembly and a factorization.
    stale = !(alpha == 1 && g.norm() <= options.reuse_contraction * s.residual);
    fresh = false;
  }
  s.seconds_total = since(start);
  return s;
}

} // namespace fibermold

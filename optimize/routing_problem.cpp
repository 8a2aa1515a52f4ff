#include "optimize/routing_problem.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "core/elapsed.hpp"
#include "core/units.hpp"
#include "optimize/adjoint_gradient.hpp"
#include "optimize/barrier.hpp"
#include "optimize/clearance_barrier.hpp"
#include "optimize/fiber_curvature.hpp"

namespace fibermold {

namespace {

/// Each target's solves on a Newton solver of their own (up to this many), so that each starts on
/// the factorization its last solve ended with: on the walking robot, alternating two targets on
/// one solver cost every solve an assembly and a factorization at its start.
constexpr int kSolverSlots = 4;
int solver_slot(int target) { return target % kSolverSlots; }

using Clock = std::chrono::steady_clock;

constexpr double kPressureUnit = 10e3; // Pa per optimizer unit
/// The skin barrier's samples per muscle segment (0.5 mm apart at the default 2 mm segments): the
/// barrier then follows the skin closely, and between them closest_approach holds it exactly.
constexpr int kSkinSamplesPerSegment = 4;
} // namespace

SkinBarrier route_skin_barrier(const SurfaceDistance& skin, const RoutingSettings& settings, const Route& route)
{
  const HermiteSpline s(route.points, route.tangents);
  return SkinBarrier(skin, settings.skin_distance, settings.skin_band, s,
                     kSkinSamplesPerSegment * segment_count(s, settings.segments_per_length));
}

RoutingProblem::RoutingProblem(Simulation& sim, const MuscleModel& model, const SurfaceDistance& skin,
                               std::vector<Eigen::VectorXd> targets, const std::vector<TrackingSamples>& curves,
                               Routing start, RoutingSettings settings)
    : sim_(sim), model_(model), skin_(skin), targets_(std::move(targets)), base_(std::move(start)), settings_(settings)
{
  const int T = num_targets(), F = num_fibers();
  if (base_.pressures.rows() != T || base_.pressures.cols() != F)
    throw std::invalid_argument(fmt::format("the pressures are {}×{}, expected targets × fibers = {}×{}",
                                            base_.pressures.rows(), base_.pressures.cols(), T, F));
  if (!settings_.target_weights.empty() && settings_.target_weights.size() != targets_.size())
    throw std::invalid_argument(fmt::format("RoutingProblem: {} target weights for {} targets",
                                            settings_.target_weights.size(), targets_.size()));
  for (std::size_t t = 0; t < targets_.size(); ++t)
    distances_.emplace_back(sim_.basis(), curves, targets_[t],
                            settings_.target_weights.empty() ? 1.0 : settings_.target_weights[t]);
  // Every state the optimizer scores ends on a step with a fresh factorization: it lands far below
  // the tolerance, where a reused factorization stops just under it, and BFGS's line search would
  // compare objective values that differ by that noise. The adjoint solve reuses that factorization.
  sim_.newton_options().finish_on_fresh_step = true;
  warm_.assign(targets_.size(), sim_.rest());
  for (const Route& r : base_.routes) {
    const HermiteSpline s(r.points, r.tangents);
    segment_t_.push_back(segment_parameters(s, segment_count(s, settings_.segments_per_length)));
    skin_barriers_.push_back(route_skin_barrier(skin_, settings_, r));
    start_length_.push_back(s.length());
  }
  if (!fibers_inside(base_)) throw std::invalid_argument("a fiber of the starting routing leaves the body");
  if (settings_.min_bend_radius > 0) bend_barrier_.emplace(settings_.min_bend_radius);
  set_free(std::vector<bool>(F, true), Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>::Constant(T, F, true),
           std::vector<bool>(T, true));
}

void RoutingProblem::set_free(std::vector<bool> routes, Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> pressures,
                              std::vector<bool> targets)
{
  target_active_ = std::move(targets);
  best_terms_ = RoutingTerms{};
  best_terms_.total = HUGE_VAL; // the objective changed: no best yet
  best_warm_.clear();
  entries_.clear();
  entry_of_.assign(base_.routes.size(), {});
  pressure_entry_ = Eigen::MatrixXi::Constant(num_targets(), num_fibers(), -1);
  for (int f = 0; f < num_fibers(); ++f) {
    const int n = static_cast<int>(base_.routes[f].points.size());
    entry_of_[f].assign(6 * n, -1);
    if (!routes[f]) continue;
    for (int k = 0; k < n; ++k)
      for (int kind = 0; kind < 2; ++kind) {
        if (kind == 0 && (k == 0 || k == n - 1)) continue; // end points stay fixed
        for (int c = 0; c < 3; ++c) {
          entry_of_[f][6 * k + 3 * kind + c] = static_cast<int>(entries_.size());
          entries_.push_back({kind == 0 ? Entry::Point : Entry::Tangent, f, k, c});
        }
      }
  }
  for (int t = 0; t < num_targets(); ++t)
    for (int f = 0; f < num_fibers(); ++f)
      if (pressures(t, f) && target_active_[t]) {
        pressure_entry_(t, f) = static_cast<int>(entries_.size());
        entries_.push_back({Entry::Pressure, f, t, 0});
      }
}

int RoutingProblem::skin_violation(const Routing& r, double& distance, Eigen::Vector3d& where) const
{
  for (int f = 0; f < num_fibers(); ++f) {
    distance = skin_barriers_[f].closest_approach(HermiteSpline(r.routes[f].points, r.routes[f].tangents), where);
    if (distance <= settings_.skin_distance) return f;
  }
  return -1;
}

int RoutingProblem::exit_violation(const Routing& r, ExitShortfall& shortfall) const
{
  for (int f = 0; f < num_fibers(); ++f)
    if (const auto s = skin_barriers_[f].exit_shortfall(HermiteSpline(r.routes[f].points, r.routes[f].tangents))) {
      shortfall = *s;
      return f;
    }
  return -1;
}

double RoutingProblem::skin_weight() const
{
  return settings_.weight_skin / kSkinSamplesPerSegment; // weight_skin per segment, as with one sample each
}

double RoutingProblem::scale(const Entry& e) const { return e.kind == Entry::Pressure ? kPressureUnit : units::mm; }

Eigen::VectorXd RoutingProblem::variables(const Routing& r) const
{
  Eigen::VectorXd z(size());
  for (Eigen::Index i = 0; i < size(); ++i) {
    const Entry& e = entries_[i];
    const Route& route = r.routes[e.fiber];
    const double v = e.kind == Entry::Point     ? route.points[e.index][e.component]
                     : e.kind == Entry::Tangent ? route.tangents[e.index][e.component]
                                                : r.pressures(e.index, e.fiber);
    z[i] = v / scale(e);
  }
  return z;
}

Routing RoutingProblem::routing(const Eigen::VectorXd& z) const
{
  Routing r = base_;
  for (Eigen::Index i = 0; i < size(); ++i) {
    const Entry& e = entries_[i];
    Route& route = r.routes[e.fiber];
    const double v = z[i] * scale(e);
    if (e.kind == Entry::Point)
      route.points[e.index][e.component] = v;
    else if (e.kind == Entry::Tangent)
      route.tangents[e.index][e.component] = v;
    else
      r.pressures(e.index, e.fiber) = v;
  }
  return r;
}

void RoutingProblem::add_fiber_gradient(int f, const FiberParameterGradient& g, double weight, int target,
                                        Eigen::VectorXd& out) const
{
  const auto& of = entry_of_[f];
  for (std::size_t k = 0; k < g.points.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      if (const int i = of[6 * k + c]; i >= 0) out[i] += weight * g.points[k][c] * units::mm;
      if (const int i = of[6 * k + 3 + c]; i >= 0) out[i] += weight * g.tangents[k][c] * units::mm;
    }
  if (target >= 0)
    if (const int i = pressure_entry_(target, f); i >= 0) out[i] += weight * g.pressure * kPressureUnit;
}

bool RoutingProblem::fibers_inside(const Routing& r) const
{
  for (int f = 0; f < num_fibers(); ++f) {
    const HermiteSpline s(r.routes[f].points, r.routes[f].tangents);
    for (const Eigen::Vector3d& c : segments_at(s, segment_t_[f]).centres)
      if (!skin_.closest(c).inside) return false;
  }
  return true;
}

std::vector<std::unique_ptr<MuscleEnergy>> RoutingProblem::muscles(const Routing& r, int t) const
{
  std::vector<std::unique_ptr<MuscleEnergy>> out;
  for (int f = 0; f < num_fibers(); ++f)
    out.push_back(std::make_unique<MuscleEnergy>(sim_.basis(), model_,
                                                 HermiteSpline(r.routes[f].points, r.routes[f].tangents), segment_t_[f],
                                                 r.pressures(t, f)));
  return out;
}

bool RoutingProblem::solve(int t, std::vector<std::unique_ptr<Energy>> energies, Eigen::VectorXd& x)
{
  sim_.use_solver(solver_slot(t));
  sim_.set_variable_energies(std::move(energies));
  NullProgress progress; // still honours Ctrl-C
  const auto start = Clock::now();
  // From the best design's equilibrium, not the last trial's: a body with more than one
  // equilibrium (the walking robot's legs) can settle on another branch at a long trial step,
  // and the trials after it would start on that branch and score the base design higher than
  // it was (by 0.096 of 2.13 at the stall of session 14, where the line search then failed).
  x = best_warm_.empty() ? warm_[t] : best_warm_[t];
  NewtonSummary s = sim_.solve(x, progress);
  newton_ += s;
  if (!s.converged) { // a warm start far from the answer can fail where the rest state does not
    x = sim_.rest();
    s = sim_.solve(x, progress);
    newton_ += s;
  }
  seconds_simulation_ += since(start);
  if (s.converged) warm_[t] = x;
  return s.converged;
}

Eigen::VectorXd RoutingProblem::equilibrium(const Routing& r, int t)
{
  std::vector<std::unique_ptr<Energy>> energies;
  for (auto& m : muscles(r, t)) energies.push_back(std::move(m));
  Eigen::VectorXd x;
  if (!solve(t, std::move(energies), x)) throw std::runtime_error(fmt::format("no equilibrium for target {}", t + 1));
  return x;
}

double RoutingProblem::regularizers(const Routing& r, Eigen::VectorXd* gradient, RoutingTerms& terms) const
{
  for (int f = 0; f < num_fibers(); ++f) {
    if (entry_of_[f].empty() || std::all_of(entry_of_[f].begin(), entry_of_[f].end(), [](int i) { return i < 0; }))
      continue; // a fixed route adds a constant
    const HermiteSpline s(r.routes[f].points, r.routes[f].tangents);
    const double wc = settings_.weight_curvature * start_length_[f];
    terms.curvature += wc * fiber_curvature(s);
    terms.skin += skin_weight() * skin_barriers_[f].value(s);
    if (!std::isfinite(terms.skin)) return refuse("skin distance");
    Eigen::Vector3d where; // between the barrier's samples too (a notch's bottom between two)
    if (skin_barriers_[f].closest_approach(s, where, true) <= settings_.skin_distance) return refuse("skin distance");
    if (bend_barrier_) {
      // The barrier's samples, and between them the spline's exact smallest radius.
      terms.bend += settings_.weight_bend * bend_barrier_->value(s);
      if (!std::isfinite(terms.bend) || smallest_bend(s).radius <= settings_.min_bend_radius)
        return refuse("bend radius");
    }
    if (gradient) add_route_gradient(r, f, *gradient);
  }
  const double pmax = settings_.max_pressure, margin = settings_.pressure_margin;
  for (int t = 0; t < num_targets(); ++t)
    for (int f = 0; f < num_fibers(); ++f) {
      const int i = pressure_entry_(t, f);
      if (i < 0) continue;
      const double u = r.pressures(t, f) / pmax;
      terms.pressure += settings_.weight_pressure * (barrier(u, margin) + barrier(1 - u, margin));
      if (!std::isfinite(terms.pressure)) return refuse("pressure limit");
      if (gradient)
        (*gradient)[i] += settings_.weight_pressure * (barrier_gradient(u, margin) - barrier_gradient(1 - u, margin)) /
                          pmax * kPressureUnit;
    }
  if (clearance_barrier_) {
    terms.clearance = weight_clearance_ * clearance_barrier_->value(r.routes);
    if (!std::isfinite(terms.clearance)) return refuse("fibers' clearance");
    if (gradient) add_clearance_gradient(r, *gradient);
  }
  return terms.curvature + terms.skin + terms.bend + terms.pressure + terms.clearance;
}

void RoutingProblem::add_route_gradient(const Routing& r, int f, Eigen::VectorXd& out) const
{
  const HermiteSpline s(r.routes[f].points, r.routes[f].tangents);
  add_fiber_gradient(f, fiber_curvature_gradient(s), settings_.weight_curvature * start_length_[f], -1, out);
  add_fiber_gradient(f, skin_barriers_[f].gradient(s), skin_weight(), -1, out);
  if (bend_barrier_) add_fiber_gradient(f, bend_barrier_->gradient(s), settings_.weight_bend, -1, out);
}

void RoutingProblem::add_clearance_gradient(const Routing& r, Eigen::VectorXd& out, int only) const
{
  const std::vector<FiberParameterGradient> g = clearance_barrier_->gradient(r.routes, only);
  for (int f = 0; f < num_fibers(); ++f) add_fiber_gradient(f, g[f], weight_clearance_, -1, out);
}

Eigen::MatrixXd RoutingProblem::regularizer_hessian(const Eigen::VectorXd& z) const
{
  // Variables in mm and 10 kPa: 1e-6 is a nanometre, far inside every barrier's band.
  constexpr double h = 1e-6;
  const Eigen::Index n = size();
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  // A column moves one fiber's route: of the clearance barrier, only its pairs with that fiber
  // change (the others cancel in the difference), and only they are measured.
  const auto route_gradient = [&](const Eigen::VectorXd& at, int f) {
    const Routing r = routing(at);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
    add_route_gradient(r, f, g);
    if (clearance_barrier_) add_clearance_gradient(r, g, f);
    return g;
  };
  const Routing r = routing(z);
  const double pmax = settings_.max_pressure, margin = settings_.pressure_margin;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Entry& e = entries_[i];
    if (e.kind == Entry::Pressure) {
      const double u = r.pressures(e.index, e.fiber) / pmax;
      H(i, i) = settings_.weight_pressure * (barrier_hessian(u, margin) + barrier_hessian(1 - u, margin)) *
                std::pow(kPressureUnit / pmax, 2);
      continue;
    }
    Eigen::VectorXd up = z, down = z;
    up[i] += h;
    down[i] -= h;
    H.col(i) = (route_gradient(up, e.fiber) - route_gradient(down, e.fiber)) / (2 * h);
  }
  // Projected onto the positive semi-definite matrices (negative eigenvalues to zero, as Newton on
  // an IPC barrier projects its Hessian): the curvature term and a barrier across a concave skin
  // are not convex, and an indefinite model has no minimum to step to.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen((H + H.transpose()) / 2);
  return eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0).asDiagonal() * eigen.eigenvectors().transpose();
}

double RoutingProblem::regularizer_value(const Eigen::VectorXd& z) const
{
  const Routing r = routing(z);
  RoutingTerms terms;
  counting_refusals_ = false;
  const double value = regularizers(r, nullptr, terms);
  counting_refusals_ = true;
  return std::isfinite(value) && fibers_inside(r) ? value : HUGE_VAL;
}

void RoutingProblem::regularizer_derivatives(const Eigen::VectorXd& z, Eigen::VectorXd& gradient,
                                             Eigen::MatrixXd& hessian) const
{
  if (last_regularizer_.z.size() == z.size() && last_regularizer_.z == z) {
    gradient = last_regularizer_.gradient;
    hessian = last_regularizer_.hessian;
    return;
  }
  RoutingTerms terms;
  gradient = Eigen::VectorXd::Zero(size());
  counting_refusals_ = false;
  regularizers(routing(z), &gradient, terms);
  counting_refusals_ = true;
  hessian = regularizer_hessian(z);
}

Eigen::MatrixXd RoutingProblem::mixed_columns(int t, const Eigen::VectorXd& x,
                                              const std::vector<const MuscleEnergy*>& muscles,
                                              std::vector<Eigen::Index>& columns) const
{
  columns.clear();
  std::vector<std::pair<int, int>> source; // (fiber, column of its mixed_columns)
  for (int f = 0; f < num_fibers(); ++f) {
    for (std::size_t c = 0; c < entry_of_[f].size(); ++c)
      if (entry_of_[f][c] >= 0) {
        columns.push_back(entry_of_[f][c]);
        source.emplace_back(f, static_cast<int>(c));
      }
    if (pressure_entry_(t, f) >= 0) {
      columns.push_back(pressure_entry_(t, f));
      source.emplace_back(f, static_cast<int>(entry_of_[f].size()));
    }
  }
  Eigen::MatrixXd M(x.size(), static_cast<Eigen::Index>(columns.size()));
  std::vector<Eigen::MatrixXd> by_fiber(muscles.size());
  for (std::size_t k = 0; k < source.size(); ++k) {
    const auto [f, c] = source[k];
    if (by_fiber[f].size() == 0) by_fiber[f] = muscles[f]->mixed_columns(x);
    M.col(static_cast<Eigen::Index>(k)) = by_fiber[f].col(c) * scale(entries_[columns[k]]);
  }
  return M;
}

Eigen::MatrixXd RoutingProblem::sensitivities(const Routing& r, int t, const Eigen::VectorXd& x)
{
  const auto owned = muscles(r, t);
  std::vector<const MuscleEnergy*> m;
  for (const auto& e : owned) m.push_back(e.get());
  std::vector<Eigen::Index> columns;
  const Eigen::MatrixXd M = mixed_columns(t, x, m, columns);
  sim_.use_solver(solver_slot(t));
  Eigen::MatrixXd S;
  if (!sim_.solver().solve_with_factorization(M, S)) return {};
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(x.size(), size());
  for (std::size_t k = 0; k < columns.size(); ++k) out.col(columns[k]) = -S.col(static_cast<Eigen::Index>(k));
  return out;
}

double RoutingProblem::evaluate(const Eigen::VectorXd& z, Eigen::VectorXd* gradient, RoutingTerms* terms_out,
                                Eigen::MatrixXd* model)
{
  if (model && !gradient) throw std::invalid_argument("RoutingProblem::evaluate: a model Hessian needs the gradient");
  const Routing r = routing(z);
  RoutingTerms terms;
  terms.per_target.assign(targets_.size(), 0);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(size());
  Eigen::MatrixXd B;
  if (model) B = Eigen::MatrixXd::Zero(size(), size());
  if (!std::isfinite(regularizers(r, gradient ? &g : nullptr, terms))) return HUGE_VAL; // counted where refused
  if (!fibers_inside(r)) return refuse("outside the body");
  const Eigen::VectorXd regularizer_gradient = g;
  for (int t = 0; t < num_targets(); ++t) {
    if (!target_active_[t]) continue;
    auto owned = muscles(r, t);
    std::vector<const MuscleEnergy*> m;
    std::vector<std::unique_ptr<Energy>> energies;
    for (auto& e : owned) {
      m.push_back(e.get());
      energies.push_back(std::move(e));
    }
    Eigen::VectorXd x;
    if (!solve(t, std::move(energies), x)) return refuse("no equilibrium");
    terms.per_target[t] = distances_[t].value(x);
    terms.distance += terms.per_target[t];
    if (!gradient) continue;
    const auto start = Clock::now();
    std::vector<FiberParameterGradient> by_fiber;
    try {
      by_fiber = adjoint_gradient(sim_, x, distances_[t].gradient(x), m);
    } catch (const std::runtime_error&) {
      return refuse("unstable equilibrium"); // no gradient to follow
    }
    seconds_adjoint_ += since(start);
    for (int f = 0; f < num_fibers(); ++f) add_fiber_gradient(f, by_fiber[f], 1.0, t, g);
    if (!model) continue;
    const auto model_start = Clock::now();
    std::vector<Eigen::Index> columns;
    const Eigen::MatrixXd M = mixed_columns(t, x, m, columns);
    Eigen::MatrixXd S; // −dx/dz over `columns`: the sign drops out of SᵀQS
    if (!sim_.solver().solve_with_factorization(M, S)) return refuse("unstable equilibrium");
    const Eigen::MatrixXd gn = distances_[t].gauss_newton_hessian(S);
    for (std::size_t a = 0; a < columns.size(); ++a)
      for (std::size_t b = 0; b < columns.size(); ++b)
        B(columns[a], columns[b]) += gn(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
    seconds_model_ += since(model_start);
  }
  terms.total = terms.distance + terms.curvature + terms.skin + terms.bend + terms.pressure + terms.clearance;
  if (gradient) *gradient = g;
  if (model) {
    const auto model_start = Clock::now();
    last_regularizer_ = {z, regularizer_gradient, regularizer_hessian(z)};
    *model = B + last_regularizer_.hessian;
    seconds_model_ += since(model_start);
  }
  if (terms_out) *terms_out = terms;
  last_terms_ = terms;
  if (terms.total < best_terms_.total) {
    best_terms_ = terms;
    best_warm_ = warm_;
  }
  return terms.total;
}

} // namespace fibermold

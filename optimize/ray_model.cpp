#include "optimize/ray_model.hpp"

#include <algorithm>
#include <cmath>

namespace fibermold {

namespace {

/// Halvings of the step tried, from α = 1 down to 2⁻¹².
constexpr int kHalvings = 12;
/// Golden-section iterations refining the best halving (the bracket shrinks by 0.618 each).
constexpr int kGoldenIterations = 12;

/// The α of least m(α) (ray_model.hpp) given gᵀδ, δᵀMδ, r(x) and r's expansion r₁, r₂ along δ.
RayStep search_ray(const std::function<double(const Eigen::VectorXd&)>& r, const Eigen::VectorXd& x,
                   const Eigen::VectorXd& delta, double gd, double dMd, double r0, double r1, double r2)
{
  // f − m(α): the decrease the model predicts for the step αδ.
  const auto decrease = [&](double a) {
    const double ra = r(x + a * delta);
    if (!std::isfinite(ra)) return -HUGE_VAL;
    return -(a * (gd - r1) + 0.5 * a * a * (dMd - r2) + ra - r0);
  };
  double best_alpha = 1, best = decrease(1);
  int best_k = 0;
  for (int k = 1; k <= kHalvings; ++k) {
    const double a = std::ldexp(1.0, -k), d = decrease(a);
    if (d > best) {
      best = d;
      best_alpha = a;
      best_k = k;
    } else if (std::isfinite(best)) {
      break; // past the best of the halvings: m rises again towards α = 0
    }
  }
  if (!(best > 0)) return {best_alpha, best};
  // Golden-section search for the largest decrease between the best halving's neighbours.
  double lo = best_alpha / 2, hi = best_k == 0 ? 1.0 : 2 * best_alpha;
  const double phi = (std::sqrt(5.0) - 1) / 2;
  double a = hi - phi * (hi - lo), b = lo + phi * (hi - lo), da = decrease(a), db = decrease(b);
  for (int i = 0; i < kGoldenIterations; ++i) {
    if (da >= db) {
      hi = b;
      b = a;
      db = da;
      a = hi - phi * (hi - lo);
      da = decrease(a);
    } else {
      lo = a;
      a = b;
      da = db;
      b = lo + phi * (hi - lo);
      db = decrease(b);
    }
  }
  if (da > best) return {a, da};
  if (db > best) return {b, db};
  return {best_alpha, best};
}

} // namespace

RayStep ray_step(const std::function<double(const Eigen::VectorXd&)>& r, const Eigen::VectorXd& x,
                 const Eigen::VectorXd& g, const Eigen::MatrixXd& M, const Eigen::VectorXd& delta)
{
  const double gd = g.dot(delta), dMd = delta.dot(M * delta);
  const RayStep quadratic{1, -(gd + 0.5 * dMd)};
  const double r0 = r(x), largest = delta.cwiseAbs().maxCoeff();
  if (!std::isfinite(r0) || !(largest > 0)) return quadratic;
  // r's derivatives along δ: central differences over 1e-4 of a unit in the largest variable, or
  // over half the step where the step is shorter (round-off in r₂ is about 4e-16 |r| / h²: on a
  // tiny step, near convergence, a tiny h would drown the decrease in it).
  double h = std::min(1e-4 / largest, 0.5), up = HUGE_VAL, down = HUGE_VAL;
  for (int k = 0; k < 4 && !(std::isfinite(up) && std::isfinite(down)); ++k, h /= 10) {
    up = r(x + h * delta);
    down = r(x - h * delta);
  }
  if (!(std::isfinite(up) && std::isfinite(down))) return quadratic;
  h *= 10; // the loop divided once more after the last evaluation
  return search_ray(r, x, delta, gd, dMd, r0, (up - down) / (2 * h), (up - 2 * r0 + down) / (h * h));
}

RayStep ray_step(const std::function<double(const Eigen::VectorXd&)>& r, const Eigen::VectorXd& x,
                 const Eigen::VectorXd& g, const Eigen::MatrixXd& M, const Eigen::VectorXd& delta, double r1, double r2)
{
  const double gd = g.dot(delta), dMd = delta.dot(M * delta);
  const double r0 = r(x);
  if (!std::isfinite(r0) || !(delta.cwiseAbs().maxCoeff() > 0)) return {1, -(gd + 0.5 * dMd)};
  return search_ray(r, x, delta, gd, dMd, r0, r1, r2);
}

} // namespace fibermold

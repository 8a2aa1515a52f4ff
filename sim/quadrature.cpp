#include "sim/quadrature.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fibermold {

namespace {

/// 2-point Gauss rule on [0, 1] for the weight (1 − u)^α, from its moments
/// m_k = k! α! / (k + α + 1)!: the nodes are the roots of the orthogonal quadratic u² + a u + b.
std::array<std::array<double, 2>, 2> gauss_jacobi_2(int alpha)
{
  const auto moment = [alpha](int k) {
    return std::tgamma(k + 1.0) * std::tgamma(alpha + 1.0) / std::tgamma(k + alpha + 2.0);
  };
  const double m0 = moment(0), m1 = moment(1), m2 = moment(2), m3 = moment(3);
  // m2 + a m1 + b m0 = 0,  m3 + a m2 + b m1 = 0
  const double det = m1 * m1 - m0 * m2;
  const double a = (m0 * m3 - m1 * m2) / det;
  const double b = (m2 * m2 - m1 * m3) / det;
  const double root = std::sqrt(a * a / 4 - b);
  const double u1 = -a / 2 - root, u2 = -a / 2 + root;
  const double w1 = (m1 - u2 * m0) / (u1 - u2);
  return {{{u1, w1}, {u2, m0 - w1}}};
}

TetQuadrature one_point() { return {{Eigen::Vector4d::Constant(0.25)}, {1.0}, 1}; }

TetQuadrature four_points()
{
  const double a = 0.5854101966249685, b = 0.1381966011250105;
  TetQuadrature q;
  for (int k = 0; k < 4; ++k) {
    Eigen::Vector4d p = Eigen::Vector4d::Constant(b);
    p[k] = a;
    q.barycentric.push_back(p);
    q.weights.push_back(0.25);
  }
  q.degree = 2;
  return q;
}

TetQuadrature eight_points()
{
  // Collapsed coordinates: x1 = u, x2 = v(1 − u), x3 = w(1 − u)(1 − v), dV = 6|T| (1 − u)²(1 − v) du dv dw.
  const auto U = gauss_jacobi_2(2), V = gauss_jacobi_2(1), W = gauss_jacobi_2(0);
  TetQuadrature q;
  for (const auto& [u, wu] : U)
    for (const auto& [v, wv] : V)
      for (const auto& [w, ww] : W) {
        const double x1 = u, x2 = v * (1 - u), x3 = w * (1 - u) * (1 - v);
        q.barycentric.emplace_back(1 - x1 - x2 - x3, x1, x2, x3);
        q.weights.push_back(6 * wu * wv * ww);
      }
  q.degree = 3;
  return q;
}

} // namespace

const TetQuadrature& tet_quadrature(int points)
{
  static const TetQuadrature one = one_point(), four = four_points(), eight = eight_points();
  switch (points) {
  case 1:
    return one;
  case 4:
    return four;
  case 8:
    return eight;
  default:
    throw std::invalid_argument("no tet quadrature with " + std::to_string(points) + " points");
  }
}

} // namespace fibermold

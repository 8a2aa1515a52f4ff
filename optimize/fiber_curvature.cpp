#include "optimize/fiber_curvature.hpp"

#include <Eigen/Geometry>

namespace fibermold {

namespace {

constexpr double kX[5] = {0.0469100770306680, 0.2307653449471585, 0.5, 0.7692346550528415, 0.9530899229693320};
constexpr double kW[5] = {0.1184634425280945, 0.2393143352496832, 0.2844444444444444, 0.2393143352496832,
                          0.1184634425280945};

template <typename Visit> void for_each_quadrature_point(const HermiteSpline& s, Visit visit)
{
  const auto& P = s.points();
  const auto& T = s.tangents();
  for (int k = 0; k < s.spans(); ++k)
    for (int i = 0; i < 5; ++i) {
      double d1[4], d2[4];
      hermite_derivative_weights(kX[i], d1, d2);
      const Eigen::Vector3d* c[4] = {&P[k], &T[k], &P[k + 1], &T[k + 1]};
      Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero(); // p', p''
      for (int m = 0; m < 4; ++m) {
        a += d1[m] * *c[m];
        b += d2[m] * *c[m];
      }
      visit(k, kW[i], a, b, d1, d2);
    }
}

} // namespace

double fiber_curvature(const HermiteSpline& spline)
{
  double R = 0;
  for_each_quadrature_point(spline,
                            [&](int, double w, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const double*,
                                const double*) { R += w * a.cross(b).squaredNorm() / std::pow(a.norm(), 5); });
  return R;
}

FiberParameterGradient fiber_curvature_gradient(const HermiteSpline& spline)
{
  FiberParameterGradient g;
  g.points.assign(spline.points().size(), Eigen::Vector3d::Zero());
  g.tangents.assign(spline.points().size(), Eigen::Vector3d::Zero());
  for_each_quadrature_point(spline, [&](int k, double w, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                        const double* d1, const double* d2) {
    // f = |c|² / |a|⁵, c = a × b:  ∂f/∂a = 2 (b × c)/|a|⁵ − 5 |c|² a/|a|⁷,  ∂f/∂b = 2 (c × a)/|a|⁵
    const Eigen::Vector3d c = a.cross(b);
    const double na = a.norm(), na5 = std::pow(na, 5);
    const Eigen::Vector3d by_a = w * (2 * b.cross(c) / na5 - 5 * c.squaredNorm() * a / (na5 * na * na));
    const Eigen::Vector3d by_b = w * 2 * c.cross(a) / na5;
    Eigen::Vector3d* out[4] = {&g.points[k], &g.tangents[k], &g.points[k + 1], &g.tangents[k + 1]};
    for (int m = 0; m < 4; ++m) *out[m] += d1[m] * by_a + d2[m] * by_b;
  });
  return g;
}

} // namespace fibermold

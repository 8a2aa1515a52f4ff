#include "sim/quadrature.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace fibermold {
namespace {

/// ∫_T λ0^a λ1^b λ2^c λ3^d dV / |T| = 6 a! b! c! d! / (a + b + c + d + 3)!
double exact(int a, int b, int c, int d)
{
  const auto f = [](int k) { return std::tgamma(k + 1.0); };
  return 6 * f(a) * f(b) * f(c) * f(d) / f(a + b + c + d + 3);
}

TEST(TetQuadrature, IntegratesEveryMonomialUpToItsDegreeExactly)
{
  for (int points : {1, 4, 8}) {
    const TetQuadrature& q = tet_quadrature(points);
    ASSERT_EQ(q.weights.size(), static_cast<std::size_t>(points));
    int checked = 0;
    for (int a = 0; a <= q.degree; ++a)
      for (int b = 0; a + b <= q.degree; ++b)
        for (int c = 0; a + b + c <= q.degree; ++c)
          for (int d = 0; a + b + c + d <= q.degree; ++d) {
            double sum = 0;
            for (std::size_t k = 0; k < q.weights.size(); ++k) {
              const Eigen::Vector4d& l = q.barycentric[k];
              sum += q.weights[k] * std::pow(l[0], a) * std::pow(l[1], b) * std::pow(l[2], c) * std::pow(l[3], d);
            }
            EXPECT_NEAR(sum, exact(a, b, c, d), 1e-14) << points << " points, exponents " << a << b << c << d;
            ++checked;
          }
    EXPECT_GT(checked, 0);
  }
  // The 8-point rule is not exact beyond degree 3.
  const TetQuadrature& q8 = tet_quadrature(8);
  double sum = 0;
  for (std::size_t k = 0; k < 8; ++k) sum += q8.weights[k] * std::pow(q8.barycentric[k][1], 4);
  EXPECT_GT(std::abs(sum - exact(0, 4, 0, 0)), 1e-6);
  for (const auto& l : q8.barycentric) EXPECT_GT(l.minCoeff(), 0); // all points inside
  EXPECT_THROW(tet_quadrature(5), std::invalid_argument);
}

} // namespace
} // namespace fibermold

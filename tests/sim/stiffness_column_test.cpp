#include "sim/stiffness_column.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "sim/neo_hookean.hpp"

namespace fibermold {
namespace {

// Node column j = 0 with neighbours 0..4 (stride 15, 3 block columns; padded: stride 20, each
// block column with a fourth, unused entry), framed by sentinels so that a write outside the column
// shows. The point couples node j to nodes 1, 2 and 4 (the last one).
// The sentinels are signalling NaNs: even a read-modify-write that adds zero (a 4-wide update of a
// 3-entry block column, which would race with the thread that owns the next column) quiets them.
const std::uint64_t kSentinel = std::bit_cast<std::uint64_t>(std::numeric_limits<double>::signaling_NaN());

struct Column {
  static constexpr int kNeighbours = 5, kGuard = 4;
  bool padded;
  int lanes = padded ? 4 : 3, stride = lanes * kNeighbours;
  std::vector<double> storage = std::vector<double>(3 * stride + 2 * kGuard, std::bit_cast<double>(kSentinel));
  std::vector<int> position{0, lanes, 2 * lanes, 3 * lanes, 4 * lanes};

  explicit Column(bool padded = false) : padded(padded)
  {
    std::fill(storage.begin() + kGuard, storage.end() - kGuard, 0.0);
  }
  StiffnessColumn view() { return {storage.data() + kGuard, stride, position.data(), padded}; }
  double block(int k, int a, int b) const { return storage[kGuard + b * stride + lanes * k + a]; }
  bool sentinels_intact() const
  {
    for (int k = 0; k < kGuard; ++k)
      if (std::bit_cast<std::uint64_t>(storage[k]) != kSentinel ||
          std::bit_cast<std::uint64_t>(storage[storage.size() - 1 - k]) != kSentinel)
        return false;
    return true;
  }
};

/// The point couples node j (gradient gj) to nodes 1, 2 and 4 (gradients gi).
struct Coupling {
  Eigen::Vector3d gj;
  std::vector<Eigen::Vector3d> gi;
  std::vector<int> nodes;
};

Coupling random_coupling(std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1, 1);
  const auto random = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  return {random(), {random(), random(), random()}, {1, 2, 4}};
}

TEST(StiffnessColumn, BothKernelsAddTheContractionOfTheStressDerivativeAndStayInTheColumn)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Matrix<double, 9, 9> VC;
  for (int r = 0; r < 9; ++r)
    for (int s = 0; s < 9; ++s) VC(r, s) = u(rng);
  const StiffnessLayout W = stiffness_layout(VC);
  const auto [gj, gi, nodes] = random_coupling(rng);

  for (const bool simd : {false, true})
    for (const bool padded : {false, true}) {
      SCOPED_TRACE(simd ? "AVX2" : "portable");
      SCOPED_TRACE(padded ? "padded" : "3 entries per block column");
      if (simd && !stiffness_simd_available()) GTEST_SKIP() << "no AVX2 and FMA on this processor";
      Column column(padded);
      add_point_to_column(W.data(), gj, gi.data(), nodes.data(), 3, column.view(), simd);
      add_point_to_column(W.data(), gj, gi.data(), nodes.data(), 3, column.view(), simd); // accumulates
      for (int n = 0; n < 3; ++n)
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) {
            double expected = 0;
            for (int c = 0; c < 3; ++c)
              for (int d = 0; d < 3; ++d) expected += VC(3 * a + c, 3 * b + d) * gi[n][c] * gj[d];
            EXPECT_NEAR(column.block(nodes[n], a, b), 2 * expected, 1e-14)
                << "node " << nodes[n] << " entry " << a << b;
          }
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          EXPECT_EQ(column.block(0, a, b), 0.0);
          EXPECT_EQ(column.block(3, a, b), 0.0);
        }
      for (int k = 0; padded && k < Column::kNeighbours; ++k)
        for (int b = 0; b < 3; ++b) {
          EXPECT_EQ(column.block(k, 3, b), 0.0) << "the padding of block " << k << " column " << b;
        }
      EXPECT_TRUE(column.sentinels_intact());
    }
}

// The structured kernel against the general one fed the same point's V ∂P/∂F: the exact Hessian
// is assembled with it, the projected one with the general one.
TEST(StiffnessColumn, TheNeoHookeanKernelAddsWhatTheGeneralOneAddsForItsStressDerivative)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  const LameParameters lame = LameParameters::from_young_poisson(86.4e3, 0.47);
  const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + 0.4 * Eigen::Matrix3d::NullaryExpr([&] { return u(rng); });
  ASSERT_GT(F.determinant(), 0);
  const double V = 2.5e-9;
  const Eigen::Matrix3d G = F.inverse().transpose();
  const NeoHookeanPoint point{G, V * lame.mu, V * lame.lambda, V * (lame.mu - lame.lambda * std::log(F.determinant()))};
  const StiffnessLayout W = stiffness_layout(V * neo_hookean_stress_derivative(F, lame));
  const auto [gj, gi, nodes] = random_coupling(rng);
  for (const bool simd : {false, true})
    for (const bool padded : {false, true}) {
      SCOPED_TRACE(simd ? "AVX2" : "portable");
      SCOPED_TRACE(padded ? "padded" : "3 entries per block column");
      if (simd && !stiffness_simd_available()) GTEST_SKIP() << "no AVX2 and FMA on this processor";
      Column general(padded), structured(padded);
      add_point_to_column(W.data(), gj, gi.data(), nodes.data(), 3, general.view(), simd);
      add_neo_hookean_point_to_column(point, gj, gi.data(), nodes.data(), 3, structured.view(), simd);
      double largest = 0;
      for (double v : general.storage) largest = std::max(largest, std::isnan(v) ? 0.0 : std::abs(v));
      ASSERT_GT(largest, 0);
      for (std::size_t k = Column::kGuard; k + Column::kGuard < general.storage.size(); ++k)
        EXPECT_NEAR(structured.storage[k], general.storage[k], 1e-13 * largest) << "entry " << k - Column::kGuard;
      EXPECT_TRUE(structured.sentinels_intact());
    }
}

} // namespace
} // namespace fibermold

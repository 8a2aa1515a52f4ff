#include "sim/stiffness_column.hpp"

#include <bit>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace fibermold {
namespace {

// Node column j = 0 with neighbours 0..4 (stride 15, 3 block columns), framed by sentinels so that
// a write outside the column shows. The point couples node j to nodes 1, 2 and 4 (the last one).
// The sentinels are signalling NaNs: even a read-modify-write that adds zero (a 4-wide update of a
// 3-entry block column, which would race with the thread that owns the next column) quiets them.
const std::uint64_t kSentinel = std::bit_cast<std::uint64_t>(std::numeric_limits<double>::signaling_NaN());

struct Column {
  static constexpr int kNeighbours = 5, kStride = 3 * kNeighbours, kGuard = 4;
  std::vector<double> storage = std::vector<double>(3 * kStride + 2 * kGuard, std::bit_cast<double>(kSentinel));
  std::vector<int> position{0, 3, 6, 9, 12};

  Column() { std::fill(storage.begin() + kGuard, storage.end() - kGuard, 0.0); }
  StiffnessColumn view() { return {storage.data() + kGuard, kStride, position.data()}; }
  double block(int k, int a, int b) const { return storage[kGuard + b * kStride + 3 * k + a]; }
};

TEST(StiffnessColumn, BothKernelsAddTheContractionOfTheStressDerivativeAndStayInTheColumn)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Matrix<double, 9, 9> VC;
  for (int r = 0; r < 9; ++r)
    for (int s = 0; s < 9; ++s) VC(r, s) = u(rng);
  const StiffnessLayout W = stiffness_layout(VC);
  const Eigen::Vector3d gj(u(rng), u(rng), u(rng));
  const std::vector<Eigen::Vector3d> gi{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
  const std::vector<int> nodes{1, 2, 4};

  for (const bool simd : {false, true}) {
    SCOPED_TRACE(simd ? "AVX2" : "portable");
    if (simd && !stiffness_simd_available()) GTEST_SKIP() << "no AVX2 and FMA on this processor";
    Column column;
    add_point_to_column(W.data(), gj, gi.data(), nodes.data(), 3, column.view(), simd);
    add_point_to_column(W.data(), gj, gi.data(), nodes.data(), 3, column.view(), simd); // accumulates
    for (int n = 0; n < 3; ++n)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          double expected = 0;
          for (int c = 0; c < 3; ++c)
            for (int d = 0; d < 3; ++d) expected += VC(3 * a + c, 3 * b + d) * gi[n][c] * gj[d];
          EXPECT_NEAR(column.block(nodes[n], a, b), 2 * expected, 1e-14) << "node " << nodes[n] << " entry " << a << b;
        }
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        EXPECT_EQ(column.block(0, a, b), 0.0);
        EXPECT_EQ(column.block(3, a, b), 0.0);
      }
    for (int k = 0; k < Column::kGuard; ++k) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(column.storage[k]), kSentinel) << "sentinel " << k << " before the column";
      EXPECT_EQ(std::bit_cast<std::uint64_t>(column.storage[Column::kGuard + 3 * Column::kStride + k]), kSentinel)
          << "sentinel " << k << " after the column";
    }
  }
}

} // namespace
} // namespace fibermold

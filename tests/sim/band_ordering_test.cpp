// band_ordering: a permutation that keeps each node's coordinates together and numbers a long body
// along its length, whatever its nodes' numbering.
#include "sim/band_ordering.hpp"

#include <algorithm>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

#include "sim_fixtures.hpp"

namespace fibermold {
namespace {

/// The largest distance of an entry from the diagonal with the rows in `order`.
int bandwidth(const Eigen::SparseMatrix<double>& upper, const std::vector<int>& order)
{
  std::vector<int> position(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) position[static_cast<std::size_t>(order[k])] = static_cast<int>(k);
  int width = 0;
  for (int j = 0; j < upper.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(upper, j); it; ++it)
      width = std::max(width,
                       std::abs(position[static_cast<std::size_t>(it.row())] - position[static_cast<std::size_t>(j)]));
  return width;
}

/// The envelope (profile) with the rows in `order`: for each row, the distance from its first
/// entry left of the diagonal to the diagonal, summed: the entries a profile (skyline) factor holds.
long long envelope(const Eigen::SparseMatrix<double>& upper, const std::vector<int>& order)
{
  std::vector<int> position(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) position[static_cast<std::size_t>(order[k])] = static_cast<int>(k);
  std::vector<int> first(order.size());
  std::iota(first.begin(), first.end(), 0);
  for (int j = 0; j < upper.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(upper, j); it; ++it) {
      const int a = position[static_cast<std::size_t>(it.row())], b = position[static_cast<std::size_t>(j)];
      int& row_first = first[static_cast<std::size_t>(std::max(a, b))];
      row_first = std::min(row_first, std::min(a, b));
    }
  long long sum = 0;
  for (std::size_t k = 0; k < first.size(); ++k) sum += static_cast<long long>(k) - first[k];
  return sum;
}

TEST(BandOrdering, NumbersAShuffledLongBodyAlongItsLengthAndKeepsEachNodeWhole)
{
  // 3 × 3 × 40 nodes, each coupled to every node within two grid steps. Numbered slice by slice
  // along the bar, its bandwidth is 3 (2 · 9 + 2 · 3 + 2) + 2 = 80.
  const Eigen::SparseMatrix<double> grid = test::wide_stencil_matrix(3, 3, 40);
  std::vector<int> identity(grid.rows());
  std::iota(identity.begin(), identity.end(), 0);
  ASSERT_EQ(bandwidth(grid, identity), 80);
  std::vector<int> node_of(360);
  std::iota(node_of.begin(), node_of.end(), 0);
  std::shuffle(node_of.begin(), node_of.end(), std::mt19937(7));
  const Eigen::SparseMatrix<double> shuffled = test::renumbered(grid, node_of);
  EXPECT_GT(bandwidth(shuffled, identity), 900);

  const std::vector<int> order = band_ordering(shuffled);
  ASSERT_EQ(order.size(), 1080u);
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, identity);
  for (std::size_t k = 0; k < order.size(); k += 3) {
    EXPECT_EQ(order[k] % 3, 0) << k;
    EXPECT_EQ(order[k + 1], order[k] + 1) << k;
    EXPECT_EQ(order[k + 2], order[k] + 2) << k;
  }
  // Along the bar: an entry spans at most a few slices (27 rows each; numbered slice by slice,
  // 80 rows), and the profile is no larger than slice by slice's.
  EXPECT_LE(bandwidth(shuffled, order), 6 * 27);
  EXPECT_LE(envelope(shuffled, order), envelope(grid, identity));
}

TEST(BandOrdering, AWideBodysProfileIsSmallerThanSliceBySlice)
{
  // 8 × 6 × 30 nodes reaching three steps, shuffled: Sloan's numbering holds fewer profile entries
  // than numbering slice by slice does (a front that grows and shrinks within each slice).
  const Eigen::SparseMatrix<double> grid = test::wide_stencil_matrix(8, 6, 30, 3);
  std::vector<int> identity(grid.rows());
  std::iota(identity.begin(), identity.end(), 0);
  std::vector<int> node_of(8 * 6 * 30);
  std::iota(node_of.begin(), node_of.end(), 0);
  std::shuffle(node_of.begin(), node_of.end(), std::mt19937(11));
  const Eigen::SparseMatrix<double> shuffled = test::renumbered(grid, node_of);
  const long long sloan = envelope(shuffled, band_ordering(shuffled)), slices = envelope(grid, identity);
  EXPECT_LT(sloan, slices);
  RecordProperty("envelope_sloan", std::to_string(sloan));
  RecordProperty("envelope_slice_by_slice", std::to_string(slices));
}

TEST(BandOrdering, OrdersEveryComponentOfADisconnectedMatrix)
{
  // Two bars side by side, not coupled, and a lone node coupled to nothing.
  const Eigen::SparseMatrix<double> bar = test::wide_stencil_matrix(2, 2, 10);
  const Eigen::Index n = bar.rows();
  Eigen::SparseMatrix<double> both(2 * n + 3, 2 * n + 3);
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < bar.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(bar, j); it; ++it) {
      entries.emplace_back(it.row(), j, it.value());
      entries.emplace_back(it.row() + n, j + n, it.value());
    }
  for (Eigen::Index i = 2 * n; i < 2 * n + 3; ++i) entries.emplace_back(i, i, 1.0);
  both.setFromTriplets(entries.begin(), entries.end());
  const std::vector<int> order = band_ordering(both);
  ASSERT_EQ(order.size(), static_cast<std::size_t>(2 * n + 3));
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 0; k < sorted.size(); ++k) EXPECT_EQ(sorted[k], static_cast<int>(k));
  // Each bar comes out in one piece: its rows are n consecutive places of the ordering.
  for (const Eigen::Index first : {Eigen::Index{0}, n}) {
    std::vector<int> places;
    for (std::size_t k = 0; k < order.size(); ++k)
      if (order[k] >= first && order[k] < first + n) places.push_back(static_cast<int>(k));
    ASSERT_EQ(static_cast<Eigen::Index>(places.size()), n);
    EXPECT_EQ(places.back() - places.front() + 1, n) << "the bar from row " << first;
  }
}

} // namespace
} // namespace fibermold

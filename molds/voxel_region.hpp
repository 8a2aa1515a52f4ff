#pragma once
// What a shot fills, sampled on a grid whose third axis points along the pull direction (`up`):
// each voxel is, by its centre, mold (outside the cavity), fill (the liquid goes there) or solid
// (inside the cavity but taken: the cured shot-1 body and the muscles in shot 2). The fill
// simulation (fill_simulation.hpp) runs on it: k is the height in the filling stance.

#include <algorithm>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace fibermold {

struct VoxelRegion {
  double voxel = 0;                                   ///< m
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity(); ///< columns: the grid's i, j, k in the body frame (k = up)
  Eigen::Vector3i first = Eigen::Vector3i::Zero();    ///< index of voxel (0, 0, 0) in the grid
  Eigen::Vector3i size = Eigen::Vector3i::Zero();     ///< voxels along i, j, k
  enum Cell : std::uint8_t { mold = 0, fill = 1, solid = 2 };
  std::vector<std::uint8_t> cells; ///< Cell, i fastest, then j, then k

  std::int64_t index(int i, int j, int k) const
  {
    return i + static_cast<std::int64_t>(size.x()) * (j + static_cast<std::int64_t>(size.y()) * k);
  }
  bool contains(int i, int j, int k) const { return cell(i, j, k) == fill; }
  /// The cell of voxel (i, j, k); mold outside the grid.
  Cell cell(int i, int j, int k) const
  {
    if (i < 0 || j < 0 || k < 0 || i >= size.x() || j >= size.y() || k >= size.z()) return mold;
    return static_cast<Cell>(cells[static_cast<std::size_t>(index(i, j, k))]);
  }
  /// The centre of voxel (i, j, k) in the body frame, m.
  Eigen::Vector3d centre(int i, int j, int k) const
  {
    return voxel * axes * (first + Eigen::Vector3i(i, j, k)).cast<double>();
  }
  /// A body-frame point in grid coordinates (voxel units, relative to voxel (0, 0, 0)).
  Eigen::Vector3d grid(const Eigen::Vector3d& p) const { return axes.transpose() * p / voxel - first.cast<double>(); }
  std::int64_t count() const { return std::count(cells.begin(), cells.end(), std::uint8_t{fill}); } ///< fill voxels
  double volume() const { return static_cast<double>(count()) * voxel * voxel * voxel; }
};

} // namespace fibermold

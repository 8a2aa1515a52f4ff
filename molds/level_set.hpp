#pragma once
// Solids as OpenVDB narrow-band level sets: made from closed meshes or from tubes swept along a
// direction, combined by CSG, and meshed back. The geometric error of a round trip is about a tenth
// of the voxel size on smooth parts; sharp edges are rounded to about one voxel.

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "mesh/surface_mesh.hpp"
#include "molds/voxel_region.hpp"

namespace fibermold {

class LevelSet {
public:
  /// An empty solid on a grid of `voxel` (m) whose third axis points along `up`, with a band of
  /// `half_width` voxels on each side. Solids combined by CSG must share voxel and up.
  explicit LevelSet(double voxel, const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ(), double half_width = 3);
  ~LevelSet();
  LevelSet(LevelSet&&) noexcept;
  LevelSet& operator=(LevelSet&&) noexcept;

  /// The solid bounded by a closed surface (self-intersections and overlaps allowed: a union). An
  /// `exterior` band wider than half_width (voxels) leaves room for grow() without a rebuild.
  static LevelSet from_mesh(const SurfaceMesh& surface, double voxel,
                            const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ(), double half_width = 3,
                            double exterior = 0);

  LevelSet copy() const; ///< a deep copy

  /// Adds the solid swept by a ball of `radius` whose centre runs along `polyline` and, from every
  /// point of it, `length` (m) along up: a tube when length is zero, a groove open upward otherwise.
  /// With a `taper` (tan of a draft angle) the groove widens upward: its half-width grows by taper
  /// per unit of height above the fiber.
  void add_swept_tube(const std::vector<Eigen::Vector3d>& polyline, double radius, double length, double taper = 0);

  /// Grows the solid outward by by_height(h) (m, ≥ 0, at most `most`) where h is a point's height
  /// along up (m, from the frame's origin): a variable offset, φ − r(h), rebuilt as a distance field.
  /// by_height is called from several threads at once.
  void grow(const std::function<double(double)>& by_height, double most);

  void unite(LevelSet& other);     ///< this ∪ other; empties other
  void subtract(LevelSet& other);  ///< this − other; empties other
  void intersect(LevelSet& other); ///< this ∩ other; empties other

  /// The voxels whose centres lie inside (fill), on this level set's grid (its third axis along
  /// up), and those inside `taken` but not this one (solid); the grid holds both.
  VoxelRegion voxels(const LevelSet* taken = nullptr) const;

  /// A closed triangle mesh of the zero level, outward oriented; adaptivity in [0, 1] merges flat
  /// regions into fewer, larger triangles. `used` (optional) receives the adaptivity the mesh was
  /// made with: 0 when adaptive meshing kept tilting faces and the uniform mesh was returned.
  SurfaceMesh mesh(double adaptivity = 0, double* used = nullptr) const;
  double volume() const; ///< m³
  double voxel() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace fibermold

#include "molds/level_set.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <cmath>
#include <mutex>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/LevelSetMeasure.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tools/VolumeToMesh.h>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

namespace {

void initialize_once()
{
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

openvdb::FloatGrid::Ptr empty_grid(double voxel, double half_width)
{
  initialize_once();
  auto grid = openvdb::FloatGrid::create(static_cast<float>(voxel * half_width));
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  return grid;
}

double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - a - t * ab).norm();
}

/// Distance from p to the parallelogram a + s e1 + t e2, (s, t) ∈ [0, 1]².
double parallelogram_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& e1,
                              const Eigen::Vector3d& e2)
{
  Eigen::Matrix<double, 3, 2> E;
  E << e1, e2;
  const Eigen::Matrix2d G = E.transpose() * E;
  if (std::abs(G.determinant()) > 1e-30 * G.squaredNorm()) {
    const Eigen::Vector2d st = G.ldlt().solve(E.transpose() * (p - a));
    if (st.minCoeff() >= 0 && st.maxCoeff() <= 1) return (p - a - E * st).norm();
  }
  return std::min({segment_distance(p, a, a + e1), segment_distance(p, a, a + e2), segment_distance(p, a + e1, a + e1 + e2),
                   segment_distance(p, a + e2, a + e1 + e2)});
}

} // namespace

struct LevelSet::Impl {
  openvdb::FloatGrid::Ptr grid;
  double voxel, half_width;
};

LevelSet::LevelSet(double voxel, double half_width) : impl_(std::make_unique<Impl>())
{
  impl_->grid = empty_grid(voxel, half_width);
  impl_->voxel = voxel;
  impl_->half_width = half_width;
}

LevelSet::~LevelSet() = default;
LevelSet::LevelSet(LevelSet&&) noexcept = default;
LevelSet& LevelSet::operator=(LevelSet&&) noexcept = default;

double LevelSet::voxel() const { return impl_->voxel; }

LevelSet LevelSet::from_mesh(const SurfaceMesh& s, double voxel, double half_width)
{
  LevelSet out(voxel, half_width);
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  for (Eigen::Index i = 0; i < s.num_vertices(); ++i)
    points.emplace_back(static_cast<float>(s.vertices(i, 0)), static_cast<float>(s.vertices(i, 1)), static_cast<float>(s.vertices(i, 2)));
  for (Eigen::Index f = 0; f < s.num_faces(); ++f)
    triangles.emplace_back(static_cast<unsigned>(s.faces(f, 0)), static_cast<unsigned>(s.faces(f, 1)), static_cast<unsigned>(s.faces(f, 2)));
  out.impl_->grid = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(out.impl_->grid->transform(), points, triangles,
                                                                       static_cast<float>(half_width));
  return out;
}

void LevelSet::add_swept_tube(const std::vector<Eigen::Vector3d>& polyline, double radius, const Eigen::Vector3d& sweep)
{
  if (polyline.size() < 2) return;
  const double band = impl_->voxel * impl_->half_width;
  auto tube = empty_grid(impl_->voxel, impl_->half_width);
  auto acc = tube->getAccessor();
  const openvdb::math::Transform& xf = tube->transform();
  // Every voxel within the band of any piece gets the distance to the whole swept solid, so that
  // pieces overlap without leaving spurious surfaces inside one another.
  const auto distance = [&](const Eigen::Vector3d& p) {
    double d = HUGE_VAL;
    for (std::size_t k = 0; k + 1 < polyline.size(); ++k)
      d = std::min(d, parallelogram_distance(p, polyline[k], polyline[k + 1] - polyline[k], sweep));
    return d - radius;
  };
  for (std::size_t k = 0; k + 1 < polyline.size(); ++k) {
    Eigen::Vector3d lo = polyline[k].cwiseMin(polyline[k + 1]), hi = polyline[k].cwiseMax(polyline[k + 1]);
    lo = lo.cwiseMin(lo + sweep).array() - (radius + band);
    hi = hi.cwiseMax(hi + sweep).array() + (radius + band);
    const openvdb::Coord a = xf.worldToIndexCellCentered(openvdb::Vec3d(lo.x(), lo.y(), lo.z()));
    const openvdb::Coord b = xf.worldToIndexCellCentered(openvdb::Vec3d(hi.x(), hi.y(), hi.z()));
    for (int i = a.x(); i <= b.x(); ++i)
      for (int j = a.y(); j <= b.y(); ++j)
        for (int l = a.z(); l <= b.z(); ++l) {
          const openvdb::Coord c(i, j, l);
          if (acc.isValueOn(c)) continue;
          const openvdb::Vec3d w = xf.indexToWorld(c);
          const Eigen::Vector3d p(w.x(), w.y(), w.z());
          // Cheap rejection: far from this piece's own parallelogram means far from all.
          if (parallelogram_distance(p, polyline[k], polyline[k + 1] - polyline[k], sweep) - radius > band) continue;
          const double d = distance(p);
          if (d < band) acc.setValueOn(c, static_cast<float>(std::max(d, -band)));
        }
  }
  openvdb::tools::signedFloodFill(tube->tree());
  openvdb::tools::csgUnion(*impl_->grid, *tube);
}

void LevelSet::unite(LevelSet& other) { openvdb::tools::csgUnion(*impl_->grid, *other.impl_->grid); }
void LevelSet::subtract(LevelSet& other) { openvdb::tools::csgDifference(*impl_->grid, *other.impl_->grid); }

double LevelSet::volume() const { return openvdb::tools::levelSetVolume(*impl_->grid); }

SurfaceMesh LevelSet::mesh(double adaptivity) const
{
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  // Meshed a thousandth of a voxel inside the zero level: grid values of exactly zero (a groove's
  // wall on a grid plane) put the vertices of neighbouring cells at the same point, and merging them
  // pinches the mesh into non-manifold edges. Inside, not outside, so that a zero stays outside and
  // no film of zero thickness becomes solid.
  openvdb::tools::volumeToMesh(*impl_->grid, points, triangles, quads, -1e-3 * impl_->voxel, adaptivity);
  // Should two vertices still coincide, merge them and drop the faces that collapse.
  std::map<std::array<float, 3>, int> index_of;
  std::vector<int> merged(points.size());
  SurfaceMesh s;
  std::vector<Eigen::Vector3d> vertices;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto [it, added] = index_of.try_emplace({points[i].x(), points[i].y(), points[i].z()}, static_cast<int>(vertices.size()));
    if (added) vertices.emplace_back(points[i].x(), points[i].y(), points[i].z());
    merged[i] = it->second;
  }
  s.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) s.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i].transpose();
  std::vector<Eigen::Vector3i> faces;
  const auto add = [&](unsigned a, unsigned b, unsigned c) {
    const int i = merged[a], j = merged[b], k = merged[c];
    if (i != j && j != k && i != k) faces.emplace_back(i, j, k);
  };
  for (const auto& t : triangles) add(t[0], t[1], t[2]);
  for (const auto& q : quads) {
    add(q[0], q[1], q[2]);
    add(q[0], q[2], q[3]);
  }
  s.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) s.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  if (signed_volume(s) < 0) s.faces.col(1).swap(s.faces.col(2));  // OpenVDB's winding is inward
  return s;
}

} // namespace fibermold

#include "molds/level_set.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <unordered_map>

#include <Eigen/Geometry>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetMeasure.h>
#include <openvdb/tools/LevelSetRebuild.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tools/ValueTransformer.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "mesh/surface_mesh.hpp"

namespace fibermold {

namespace {

// The grids' world unit (m). OpenVDB takes a transform whose determinant is within 1e-8 of zero
// as degenerate: a rotated frame of 0.2 mm voxels in metres (det 8e-12) would fail its uniform-scale
// test, so the grids live in millimetres.
constexpr double kUnit = 1e-3;

void initialize_once()
{
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

/// Index space to world: voxel-sized cells whose third axis points along `up`.
openvdb::math::Transform::Ptr frame(double voxel, const Eigen::Vector3d& up)
{
  const Eigen::Vector3d u = up.normalized();
  const Eigen::Matrix3d R = u == Eigen::Vector3d::UnitZ()
                                ? Eigen::Matrix3d::Identity()
                                : Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), u).toRotationMatrix();
  openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = voxel * R(j, i); // OpenVDB maps row vectors: world = index · m
  return openvdb::math::Transform::createLinearTransform(m);
}

openvdb::FloatGrid::Ptr empty_grid(const openvdb::math::Transform& xf, double voxel, double half_width)
{
  initialize_once();
  auto grid = openvdb::FloatGrid::create(static_cast<float>(voxel * half_width));
  grid->setTransform(xf.copy());
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

/// One piece of a groove in index space, where up is +z: the segment ab swept `length` upward.
struct SweptSegment {
  Eigen::Vector3d a, b;
  double length;

  /// Where the segment's shadow comes closest to the column through (x, y): the horizontal
  /// distance, and the heights of the piece's bottom and top there. Between them the distance to
  /// the piece is the horizontal one.
  struct Column {
    double horizontal, bottom, top;
  };
  Column column(double x, double y) const
  {
    const Eigen::Vector2d q = Eigen::Vector2d(x, y) - a.head<2>(), e = (b - a).head<2>();
    const double len2 = e.squaredNorm();
    // A segment along up casts one shadow: the piece spans its whole height.
    if (len2 <= 1e-24) return {q.norm(), std::min(a.z(), b.z()), std::max(a.z(), b.z()) + length};
    const double s = std::clamp(q.dot(e) / len2, 0.0, 1.0);
    const double z = a.z() + s * (b.z() - a.z());
    return {(q - s * e).norm(), z, z + length};
  }

  /// Exact distance from p: to the bottom edge, the top edge, or, for the stretch of ab whose
  /// piece spans p's height, horizontally to its shadow.
  double distance(const Eigen::Vector3d& p) const
  {
    const Eigen::Vector3d up(0, 0, length);
    const double edges = std::min(segment_distance(p, a, b), segment_distance(p, a + up, b + up));
    const double dz = b.z() - a.z();
    double s0 = 0, s1 = 1; // a.z + s dz <= p.z <= a.z + s dz + length
    if (std::abs(dz) > 1e-12) {
      const double lo = (p.z() - length - a.z()) / dz, hi = (p.z() - a.z()) / dz;
      s0 = std::max(0.0, std::min(lo, hi));
      s1 = std::min(1.0, std::max(lo, hi));
    } else if (p.z() < a.z() || p.z() > a.z() + length) {
      return edges;
    }
    if (s0 > s1) return edges;
    const Eigen::Vector2d e = (b - a).head<2>(), q = p.head<2>() - a.head<2>();
    const double len2 = e.squaredNorm();
    const double s = len2 > 1e-24 ? std::clamp(q.dot(e) / len2, s0, s1) : s0;
    return std::min(edges, (q - s * e).norm());
  }
};

} // namespace

struct LevelSet::Impl {
  openvdb::FloatGrid::Ptr grid;
  double voxel, half_width;
  double exterior = 0; ///< voxels of band outside, when wider than half_width
};

LevelSet::LevelSet(double voxel, const Eigen::Vector3d& up, double half_width) : impl_(std::make_unique<Impl>())
{
  impl_->grid = empty_grid(*frame(voxel / kUnit, up), voxel / kUnit, half_width);
  impl_->voxel = voxel;
  impl_->half_width = half_width;
}

LevelSet::~LevelSet() = default;
LevelSet::LevelSet(LevelSet&&) noexcept = default;
LevelSet& LevelSet::operator=(LevelSet&&) noexcept = default;

double LevelSet::voxel() const { return impl_->voxel; }

LevelSet LevelSet::copy() const
{
  LevelSet out(impl_->voxel, Eigen::Vector3d::UnitZ(), impl_->half_width);
  out.impl_->grid = impl_->grid->deepCopy();
  out.impl_->exterior = impl_->exterior;
  return out;
}

LevelSet LevelSet::from_mesh(const SurfaceMesh& s, double voxel, const Eigen::Vector3d& up, double half_width,
                             double exterior)
{
  LevelSet out(voxel, up, half_width);
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  for (Eigen::Index i = 0; i < s.num_vertices(); ++i)
    points.emplace_back(static_cast<float>(s.vertices(i, 0) / kUnit), static_cast<float>(s.vertices(i, 1) / kUnit),
                        static_cast<float>(s.vertices(i, 2) / kUnit));
  for (Eigen::Index f = 0; f < s.num_faces(); ++f)
    triangles.emplace_back(static_cast<unsigned>(s.faces(f, 0)), static_cast<unsigned>(s.faces(f, 1)),
                           static_cast<unsigned>(s.faces(f, 2)));
  out.impl_->exterior = std::max(exterior, half_width);
  out.impl_->grid = openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(
      out.impl_->grid->transform(), points, triangles, {}, static_cast<float>(out.impl_->exterior),
      static_cast<float>(half_width));
  return out;
}

namespace {

/// Per column (i, j), the heights deep inside some piece (more than the band): those voxels are
/// skipped, and whatever another piece wrote there is cleared at the end, so that only the band
/// stays active.
using DeepSpans = std::unordered_map<std::uint64_t, std::vector<std::pair<int, int>>>;

std::uint64_t column_key(int i, int j)
{
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) | static_cast<std::uint32_t>(j);
}

/// Writes the band of one piece (distances in voxels, stored × `v` in grid units) into a grid
/// through `acc`; each voxel keeps the least distance: the union of the pieces. Above the fiber the
/// piece widens by `taper` per voxel of height (a drafted groove): there the distance to its wall,
/// inclined by atan(taper), is the horizontal one times cos(atan(taper)).
void sweep(const SweptSegment& piece, double r, double taper, double band, double v, openvdb::FloatGrid::Accessor& acc,
           DeepSpans& deep)
{
  const auto write = [&](const openvdb::Coord& c, double d) {
    if (d >= band) return;
    const float value = static_cast<float>(std::max(d, -band) * v);
    float old;
    if (!acc.probeValue(c, old))
      acc.setValueOn(c, value);
    else if (value < old)
      acc.setValue(c, value);
  };
  const double cos_a = 1 / std::sqrt(1 + taper * taper);
  const double reach = r + band + taper * piece.length;
  const Eigen::Vector3d lo = piece.a.cwiseMin(piece.b).array() - reach, hi = piece.a.cwiseMax(piece.b).array() + reach;
  const int l_lo = static_cast<int>(std::ceil(lo.z())), l_hi = static_cast<int>(std::floor(hi.z() + piece.length));
  for (int i = static_cast<int>(std::ceil(lo.x())); i <= static_cast<int>(std::floor(hi.x())); ++i)
    for (int j = static_cast<int>(std::ceil(lo.y())); j <= static_cast<int>(std::floor(hi.y())); ++j) {
      const SweptSegment::Column column = piece.column(i, j);
      const double wall = column.horizontal - r; // at the column's bottom
      const auto wall_at = [&](int l) { return (wall - taper * (l - column.bottom)) * cos_a; };
      if (wall_at(static_cast<int>(std::floor(column.top))) >= band && wall >= band) continue;
      const int bottom = static_cast<int>(std::ceil(column.bottom)), top = static_cast<int>(std::floor(column.top));
      // From this height up the column is deeper inside the piece than the band.
      const double deep_height = taper > 0 ? std::ceil(column.bottom + std::max(0.0, (wall + band / cos_a) / taper))
                                           : (wall <= -band ? bottom : top + 1);
      const int deep_from = static_cast<int>(std::min(deep_height, top + 1.0));
      const bool is_deep = std::max(bottom, deep_from) <= top;
      if (is_deep) deep[column_key(i, j)].emplace_back(std::max(bottom, deep_from), top);
      for (int l = l_lo; l <= l_hi; ++l) {
        if (l >= bottom && l <= top) {
          if (is_deep && l >= deep_from)
            l = top;
          else
            write(openvdb::Coord(i, j, l), wall_at(l));
          continue;
        }
        write(openvdb::Coord(i, j, l), piece.distance(Eigen::Vector3d(i, j, l)) - r);
      }
    }
}

} // namespace

// With a taper, the distance above a piece's top is to its untapered cap: the cap is not exact, so
// grooves are swept well out of the solid they are cut from (groove_body's `through`).
void LevelSet::add_swept_tube(const std::vector<Eigen::Vector3d>& polyline, double radius, double length, double taper)
{
  if (polyline.size() < 2) return;
  const double v = impl_->voxel / kUnit, band = impl_->half_width; // in voxels from here on
  const double r = radius / impl_->voxel;
  const openvdb::math::Transform& xf = impl_->grid->transform();
  std::vector<SweptSegment> pieces;
  const auto index = [&](const Eigen::Vector3d& w) {
    const openvdb::Vec3d i = xf.worldToIndex(openvdb::Vec3d(w.x(), w.y(), w.z()) / kUnit);
    return Eigen::Vector3d(i.x(), i.y(), i.z());
  };
  for (std::size_t k = 0; k + 1 < polyline.size(); ++k)
    pieces.push_back({index(polyline[k]), index(polyline[k + 1]), length / impl_->voxel});

  // Pieces in parallel, each thread into its own grid; then the least value of all.
  struct Partial {
    openvdb::FloatGrid::Ptr grid;
    DeepSpans deep;
  };
  tbb::enumerable_thread_specific<Partial> partials([&] { return Partial{empty_grid(xf, v, band), {}}; });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pieces.size(), 1),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      Partial& part = partials.local();
                      auto acc = part.grid->getAccessor();
                      for (std::size_t k = range.begin(); k != range.end(); ++k)
                        sweep(pieces[k], r, taper, band, v, acc, part.deep);
                    });
  openvdb::FloatGrid::Ptr tube;
  DeepSpans deep;
  for (Partial& part : partials) {
    if (!tube)
      tube = part.grid;
    else
      openvdb::tools::compMin(*tube, *part.grid);
    for (auto& [column, spans] : part.deep) deep[column].insert(deep[column].end(), spans.begin(), spans.end());
  }

  std::vector<openvdb::Coord> inside;
  const float deepest = static_cast<float>(-band * v);
  for (auto it = tube->cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    bool is_inside = *it <= deepest;
    if (const auto found = deep.find(column_key(c.x(), c.y())); !is_inside && found != deep.end())
      is_inside = std::any_of(found->second.begin(), found->second.end(),
                              [&](const auto& span) { return c.z() >= span.first && c.z() <= span.second; });
    if (is_inside) inside.push_back(c);
  }
  auto acc = tube->getAccessor();
  for (const openvdb::Coord& c : inside) acc.setValueOff(c, deepest);
  // A leaf left with no active voxel would take the sign of its first voxel, which may never have
  // been written: make such leaves tiles, whose signs the flood fill takes from their neighbours.
  openvdb::tools::pruneInactive(tube->tree());
  openvdb::tools::signedFloodFill(tube->tree());
  openvdb::tools::csgUnion(*impl_->grid, *tube);
}

void LevelSet::grow(const std::function<double(double)>& by_height, double most)
{
  // The offset surface must lie inside the band: widen it first when it is too narrow.
  if (const double needed = std::ceil(most / impl_->voxel) + impl_->half_width;
      needed > std::max(impl_->exterior, impl_->half_width))
    impl_->grid = openvdb::tools::levelSetRebuild(*impl_->grid, 0.0f, static_cast<float>(needed),
                                                  static_cast<float>(impl_->half_width));
  openvdb::tools::foreach (impl_->grid->beginValueOn(), [&](const openvdb::FloatGrid::ValueOnIter& it) {
    it.setValue(*it - static_cast<float>(by_height(it.getCoord().z() * impl_->voxel) / kUnit));
  });
  impl_->grid = openvdb::tools::levelSetRebuild(*impl_->grid, 0.0f, static_cast<float>(impl_->half_width));
  impl_->exterior = impl_->half_width;
}

void LevelSet::unite(LevelSet& other) { openvdb::tools::csgUnion(*impl_->grid, *other.impl_->grid); }
void LevelSet::subtract(LevelSet& other) { openvdb::tools::csgDifference(*impl_->grid, *other.impl_->grid); }
void LevelSet::intersect(LevelSet& other) { openvdb::tools::csgIntersection(*impl_->grid, *other.impl_->grid); }

double LevelSet::volume() const { return openvdb::tools::levelSetVolume(*impl_->grid) * kUnit * kUnit * kUnit; }

VoxelRegion LevelSet::voxels(const LevelSet* taken) const
{
  VoxelRegion out;
  out.voxel = impl_->voxel;
  const openvdb::math::Mat4d m = impl_->grid->transform().baseMap()->getAffineMap()->getMat4();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.axes(j, i) = m(i, j) / (impl_->voxel / kUnit); // world = index · m
  const openvdb::BoolGrid::Ptr fill = openvdb::tools::sdfInteriorMask(*impl_->grid, 0.0f);
  const openvdb::BoolGrid::Ptr solid = taken ? openvdb::tools::sdfInteriorMask(*taken->impl_->grid, 0.0f) : nullptr;
  openvdb::CoordBBox box = fill->evalActiveVoxelBoundingBox();
  if (solid) box.expand(solid->evalActiveVoxelBoundingBox());
  if (box.empty()) return out;
  out.first = Eigen::Vector3i(box.min().x(), box.min().y(), box.min().z());
  out.size = Eigen::Vector3i(box.dim().x(), box.dim().y(), box.dim().z());
  out.cells.assign(static_cast<std::size_t>(out.size.cast<std::int64_t>().prod()), VoxelRegion::mold);
  const auto mark = [&](const openvdb::BoolGrid& mask, VoxelRegion::Cell cell) {
    for (auto it = mask.cbeginValueOn(); it; ++it) {
      const openvdb::CoordBBox cells = it.getBoundingBox(); // one voxel, or a tile of them
      for (int k = cells.min().z(); k <= cells.max().z(); ++k)
        for (int j = cells.min().y(); j <= cells.max().y(); ++j)
          for (int i = cells.min().x(); i <= cells.max().x(); ++i)
            out.cells[static_cast<std::size_t>(out.index(i - out.first.x(), j - out.first.y(), k - out.first.z()))] =
                cell;
    }
  };
  if (solid) mark(*solid, VoxelRegion::solid);
  mark(*fill, VoxelRegion::fill);
  return out;
}

namespace {

/// The mesher's output as one triangle mesh in metres, outward oriented. Should two vertices
/// coincide, they are merged and the faces that collapse dropped.
SurfaceMesh collect(openvdb::tools::VolumeToMesh& mesher)
{
  std::map<std::array<float, 3>, int> index_of;
  std::vector<int> merged(mesher.pointListSize());
  std::vector<Eigen::Vector3d> vertices;
  for (std::size_t i = 0; i < mesher.pointListSize(); ++i) {
    const openvdb::Vec3s& p = mesher.pointList()[i];
    const auto [it, added] = index_of.try_emplace({p.x(), p.y(), p.z()}, static_cast<int>(vertices.size()));
    if (added) vertices.emplace_back(p.x() * kUnit, p.y() * kUnit, p.z() * kUnit);
    merged[i] = it->second;
  }
  std::vector<Eigen::Vector3i> faces;
  const auto add = [&](unsigned a, unsigned b, unsigned c) {
    const int i = merged[a], j = merged[b], k = merged[c];
    if (i != j && j != k && i != k) faces.emplace_back(i, j, k);
  };
  for (std::size_t n = 0; n < mesher.polygonPoolListSize(); ++n) {
    const openvdb::tools::PolygonPool& pool = mesher.polygonPoolList()[n];
    for (std::size_t t = 0; t < pool.numTriangles(); ++t)
      add(pool.triangle(t)[0], pool.triangle(t)[1], pool.triangle(t)[2]);
    for (std::size_t q = 0; q < pool.numQuads(); ++q) {
      const openvdb::Vec4I& quad = pool.quad(q);
      add(quad[0], quad[1], quad[2]);
      add(quad[0], quad[2], quad[3]);
    }
  }
  SurfaceMesh s;
  s.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i)
    s.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i].transpose();
  s.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) s.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  if (signed_volume(s) < 0) s.faces.col(1).swap(s.faces.col(2)); // OpenVDB's winding is inward
  return canonical_order(s);
}

/// Faces more than 60° off the level set's gradient (index coordinates of their centres): adaptive
/// meshing folds or tilts a few small triangles where it merges cells near thin features, and the
/// thinnest-wall check would see those as walls of almost no thickness.
constexpr double kCosFold = 0.5;
std::vector<openvdb::Coord> steep_faces(const SurfaceMesh& s, const openvdb::FloatGrid& grid)
{
  const openvdb::math::Transform& xf = grid.transform();
  const auto index = [&](const Eigen::Vector3d& w) {
    return xf.worldToIndex(openvdb::Vec3d(w.x(), w.y(), w.z()) / kUnit);
  };
  tbb::enumerable_thread_specific<std::vector<openvdb::Coord>> found;
  tbb::parallel_for(
      tbb::blocked_range<Eigen::Index>(0, s.num_faces(), 4096), [&](const tbb::blocked_range<Eigen::Index>& range) {
        const openvdb::FloatGrid::ConstAccessor acc = grid.getConstAccessor();
        const openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler> sampler(acc,
                                                                                                                 xf);
        std::vector<openvdb::Coord>& out = found.local();
        for (Eigen::Index f = range.begin(); f != range.end(); ++f) {
          const openvdb::Vec3d a = index(s.vertices.row(s.faces(f, 0))), b = index(s.vertices.row(s.faces(f, 1))),
                               c = index(s.vertices.row(s.faces(f, 2)));
          const openvdb::Vec3d normal = (b - a).cross(c - a), centre = (a + b + c) / 3;
          openvdb::Vec3d gradient;
          for (int i = 0; i < 3; ++i) {
            openvdb::Vec3d h(0);
            h[i] = 0.5;
            gradient[i] = sampler.isSample(centre + h) - sampler.isSample(centre - h);
          }
          if (normal.dot(gradient) < kCosFold * normal.length() * gradient.length())
            out.push_back(openvdb::Coord::round(centre));
        }
      });
  std::vector<openvdb::Coord> out;
  for (const auto& part : found) out.insert(out.end(), part.begin(), part.end());
  return out;
}

} // namespace

SurfaceMesh LevelSet::mesh(double adaptivity, double* used) const
{
  if (used) *used = 0;
  // Meshed a thousandth of a voxel inside the zero level: grid values of exactly zero (a groove's
  // wall on a grid plane) put the vertices of neighbouring cells at the same point, and merging them
  // pinches the mesh into non-manifold edges. Inside, not outside, so that a zero stays outside and
  // no film of zero thickness becomes solid.
  const double iso = -1e-3 * impl_->voxel / kUnit;
  const auto mesh_with = [&](double a, const openvdb::BoolTree::Ptr& uniform) {
    openvdb::tools::VolumeToMesh mesher(iso, a);
    if (uniform && !uniform->empty()) mesher.setAdaptivityMask(uniform);
    mesher(*impl_->grid);
    return collect(mesher);
  };
  SurfaceMesh s = mesh_with(0, nullptr);
  if (adaptivity == 0) return s;
  // Adaptive meshing is confined to where it tilts no face more than the uniform mesh does: cells
  // around the uniform mesh's steep faces (creases, walls thinner than a voxel) stay uniform
  // (OpenVDB's adaptivity mask), and so do cells around any face the adaptive mesh tilts, round by
  // round (the walking robot's crossing grooves need three or four). After ten rounds the uniform
  // mesh is kept.
  auto uniform = std::make_shared<openvdb::BoolTree>(false);
  constexpr int kRounds = 10, kMargin = 3; // voxels around a steep face
  const auto keep_uniform_around = [&](const std::vector<openvdb::Coord>& faces) {
    for (const openvdb::Coord& c : faces)
      uniform->fill(openvdb::CoordBBox(c.offsetBy(-kMargin), c.offsetBy(kMargin)), true, true);
  };
  keep_uniform_around(steep_faces(s, *impl_->grid));
  for (int round = 0; round < kRounds; ++round) {
    SurfaceMesh adaptive = mesh_with(adaptivity, uniform);
    std::vector<openvdb::Coord> steep = steep_faces(adaptive, *impl_->grid);
    std::erase_if(steep, [&](const openvdb::Coord& c) { return uniform->isValueOn(c); });
    if (steep.empty()) {
      if (used) *used = adaptivity;
      return adaptive;
    }
    keep_uniform_around(steep);
  }
  return s;
}

} // namespace fibermold

#include "molds/fill_simulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace fibermold {

namespace {

using Index = std::int64_t;

/// The region's voxels that a port's hole takes in: in each column within its radius (and half a
/// voxel) of its axis, coming from outside along the hole, the fill voxels it meets first, to its
/// depth past the mouth.
std::vector<Index> port_voxels(const VoxelRegion& r, const Port& p)
{
  const Eigen::Vector3d g = r.grid(p.mouth);
  const double radius = p.diameter / 2 / r.voxel + 0.5, dip = p.dip() / r.voxel + 0.5;
  std::vector<Index> out;
  const int i0 = std::max(0, static_cast<int>(std::floor(g.x() - radius))),
            i1 = std::min(r.size.x() - 1, static_cast<int>(std::ceil(g.x() + radius)));
  const int j0 = std::max(0, static_cast<int>(std::floor(g.y() - radius))),
            j1 = std::min(r.size.y() - 1, static_cast<int>(std::ceil(g.y() + radius)));
  const int step = p.upward ? -1 : 1;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      if (std::hypot(i - g.x(), j - g.y()) > radius) continue;
      int k = p.upward ? r.size.z() - 1 : 0;
      while (k >= 0 && k < r.size.z() && r.cell(i, j, k) == VoxelRegion::mold) k += step;
      for (; k >= 0 && k < r.size.z() && r.cell(i, j, k) == VoxelRegion::fill &&
             (p.upward ? k >= g.z() - dip : k <= g.z() + dip);
           k += step)
        out.push_back(r.index(i, j, k));
    }
  return out;
}

/// A voxel's state during the simulation.
enum : std::uint8_t {
  kOutside = 0, // mold, or solid (below)
  kInside = 1,  // fill, not reached yet
  kReached = 2,
  kVent = 3,    // reached, and a vent takes it in
  kCounted = 4, // fill no sprue reaches
  kSolid = 5,
};
bool is_fill(std::uint8_t s) { return s >= kInside && s <= kCounted; }

/// The simulation's own grid: the region with an empty layer of voxels around it, so that every
/// neighbour of a region voxel is in the grid and no step needs a bounds test.
struct Padded {
  Index nx, ny, nz, nxy;
  explicit Padded(const VoxelRegion& r) : nx(r.size.x() + 2), ny(r.size.y() + 2), nz(r.size.z() + 2), nxy(nx * ny) {}
  Index at(Index i, Index j, Index k) const { return (i + 1) + nx * ((j + 1) + ny * (k + 1)); } // region (i, j, k)
  Eigen::Vector3i region_ijk(Index d) const
  {
    return {static_cast<int>(d % nx - 1), static_cast<int>((d % nxy) / nx - 1), static_cast<int>(d / nxy - 1)};
  }
  /// Offsets to the 26 neighbours, the first 13 of them those that a sweep from the top down,
  /// each level in index order, meets first.
  std::vector<Index> offsets() const
  {
    std::vector<Index> before, after;
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          if (di == 0 && dj == 0 && dk == 0) continue;
          const bool met = dk == 1 || (dk == 0 && (dj < 0 || (dj == 0 && di < 0)));
          (met ? before : after).push_back(di + dj * nx + dk * nxy);
        }
    before.insert(before.end(), after.begin(), after.end());
    return before;
  }
};

/// The voxel of level k nearest (i, j) for which `member` holds, searched ring by ring (square
/// rings: the nearest in that measure).
template <class Member>
Index nearest_in_level(const VoxelRegion& r, const Padded& g, Index k, Index i, Index j, Member&& member, Index rings)
{
  const Index nx = r.size.x(), ny = r.size.y();
  for (Index ring = 0; ring <= std::min(rings, std::max(nx, ny)); ++ring)
    for (Index b = j - ring; b <= j + ring; ++b)
      for (Index a = i - ring; a <= i + ring; a += (b == j - ring || b == j + ring) ? 1 : 2 * ring) {
        if (a >= 0 && b >= 0 && a < nx && b < ny && member(g.at(a, b, k))) return g.at(a, b, k);
        if (ring == 0) break;
      }
  return -1;
}

/// The highest level of a set of voxels: its height and the sum of its voxels' (i, j).
struct Top {
  Index k = 0;
  double i = 0, j = 0;
  Index n = 0;
  Index any = -1; ///< a voxel of the level (padded grid)

  void join(const Top& o)
  {
    if (o.k > k)
      *this = o;
    else if (o.k == k)
      i += o.i, j += o.j, n += o.n;
  }
};

/// Union-find over the reached voxels in the order the top-down sweep meets them, with per set:
/// whether a vent takes it in, its voxels above the level being swept, and its highest level.
struct AirSets {
  std::vector<std::int32_t> parent;
  std::vector<std::uint8_t> rank, vented, thick; ///< thick: a voxel above the level has its 6 faces in the region
  std::vector<Index> above;
  std::vector<Top> top;

  std::int32_t add(bool vent, Index i, Index j, Index k, Index voxel)
  {
    const auto c = static_cast<std::int32_t>(parent.size());
    parent.push_back(c);
    rank.push_back(0);
    vented.push_back(vent);
    thick.push_back(0);
    above.push_back(0);
    top.push_back({k, static_cast<double>(i), static_cast<double>(j), 1, voxel});
    return c;
  }
  std::int32_t find(std::int32_t c)
  {
    while (parent[static_cast<std::size_t>(c)] != c) {
      auto& p = parent[static_cast<std::size_t>(c)];
      p = parent[static_cast<std::size_t>(p)]; // path halving
      c = p;
    }
    return c;
  }
  /// Joins the sets of a and b; a part without a vent joining one with a vent is sealed off by the
  /// liquid that reaches this level: `sealed` gets its voxels above the level and its top.
  /// Where two parts without a vent join, the smaller would be sealed off once the other has
  /// one: `nested` gets it, so that both can be vented at once.
  template <class Sealed, class Nested> void unite(std::int32_t a, std::int32_t b, Sealed&& sealed, Nested&& nested)
  {
    auto ra = static_cast<std::size_t>(find(a)), rb = static_cast<std::size_t>(find(b));
    if (ra == rb) return;
    if (vented[ra] != vented[rb]) {
      const std::size_t closed = vented[ra] ? rb : ra;
      if (above[closed] > 0) sealed(static_cast<std::int32_t>(closed), above[closed], top[closed], thick[closed]);
    } else if (!vented[ra] && above[ra] > 0 && above[rb] > 0) {
      const std::size_t smaller = above[ra] < above[rb] ? ra : rb;
      nested(static_cast<std::int32_t>(smaller), above[smaller], top[smaller], thick[smaller]);
    }
    if (rank[ra] < rank[rb]) std::swap(ra, rb);
    if (rank[ra] == rank[rb]) ++rank[ra];
    parent[rb] = static_cast<std::int32_t>(ra);
    vented[ra] = vented[ra] || vented[rb];
    thick[ra] = thick[ra] || thick[rb];
    above[ra] += above[rb];
    top[ra].join(top[rb]);
  }
};

/// One fill simulation's grids and findings; its phases in the order they run.
class FillSweep {
public:
  explicit FillSweep(const VoxelRegion& r) : r_(r), g_(r), offsets_(g_.offsets()), cell_(r.voxel * r.voxel * r.voxel)
  {
    state_.assign(static_cast<std::size_t>(g_.nxy * g_.nz), kOutside);
    for (int k = 0; k < r.size.z(); ++k)
      for (int j = 0; j < r.size.y(); ++j)
        for (int i = 0; i < r.size.x(); ++i)
          if (const auto c = r.cells[static_cast<std::size_t>(r.index(i, j, k))]; c != VoxelRegion::mold)
            state_[static_cast<std::size_t>(g_.at(i, j, k))] = c == VoxelRegion::fill ? kInside : kSolid;
    set_.assign(state_.size(), -1);
    out_.fill_volume = static_cast<double>(r.count()) * cell_;
  }

  /// What the sprues reach: the region's part connected to a sprue's voxels.
  void reach_from(const std::vector<Port>& sprues)
  {
    std::vector<Index> queue;
    for (const Port& p : sprues) {
      const std::vector<Index> mouth = voxels_of(p);
      out_.sprue_open.push_back(!mouth.empty());
      for (Index d : mouth)
        if (state(d) == kInside) state(d) = kReached, queue.push_back(d);
    }
    flood(queue, kReached);
    out_.reachable_volume = static_cast<double>(queue.size()) * cell_;
  }

  /// The parts no sprue reaches, each with its lowest point; crevices apart.
  void count_unreached()
  {
    for (Index d = 0; d < static_cast<Index>(state_.size()); ++d) {
      if (state(d) != kInside) continue;
      std::vector<Index> part{d};
      state(d) = kCounted;
      flood(part, kCounted);
      const bool crevice = std::none_of(part.begin(), part.end(), [&](Index e) { return thick_at(e); });
      if (crevice) {
        out_.crevice_volume += static_cast<double>(part.size()) * cell_;
        continue;
      }
      // Named by the voxel of its lowest level nearest that level's middle.
      const Index low = *std::min_element(part.begin(), part.end()) / g_.nxy; // k is the slowest index
      double i = 0, j = 0, n = 0;
      for (Index e : part)
        if (e / g_.nxy == low)
          i += static_cast<double>(e % g_.nx - 1), j += static_cast<double>((e % g_.nxy) / g_.nx - 1), ++n;
      const auto id = static_cast<std::int32_t>(-2 - static_cast<std::int32_t>(out_.unreachable.size()));
      for (Index e : part) set_[static_cast<std::size_t>(e)] = id;
      const Index at = nearest_in_level(
          r_, g_, low - 1, std::lround(i / n), std::lround(j / n),
          [&](Index e) { return set_[static_cast<std::size_t>(e)] == id; }, std::max(r_.size.x(), r_.size.y()));
      out_.unreachable.push_back({static_cast<double>(part.size()) * cell_, centre(at)});
    }
  }

  void open_vents(const std::vector<Port>& vents)
  {
    for (const Port& p : vents) {
      bool open = false;
      for (Index d : voxels_of(p))
        if (state(d) == kReached || state(d) == kVent) state(d) = kVent, open = true;
      out_.vent_open.push_back(open);
    }
  }

  /// The air above each level, swept from the top down: each set of air that rises into no vent
  /// is a pocket when the level above closes it off.
  void sweep_air()
  {
    std::vector<std::int32_t> level;
    std::vector<bool> level_thick;
    const auto seal = [&](std::int32_t root, Index voxels, const Top& top, bool thick) {
      const AirPocket p = pocket(root, voxels, top, thick);
      if (!thick && !p.ventable)
        out_.crevice_air_volume += p.volume;
      else
        out_.pockets.push_back(p);
    };
    const auto nested = [&](std::int32_t root, Index voxels, const Top& top, bool thick) {
      if (static_cast<double>(voxels) * cell_ >= 1e-9) out_.nested.push_back(pocket(root, voxels, top, thick));
    };
    for (Index k = r_.size.z() - 1; k >= 0; --k) {
      level.clear();
      level_thick.clear();
      for (Index j = 0; j < r_.size.y(); ++j)
        for (Index i = 0, d = g_.at(0, j, k); i < r_.size.x(); ++i, ++d) {
          const std::uint8_t s = state(d);
          if (s != kReached && s != kVent) continue;
          const std::int32_t c = air_.add(s == kVent, i, j, k, d);
          set_[static_cast<std::size_t>(d)] = c;
          level.push_back(c);
          level_thick.push_back(thick_at(d));
          for (std::size_t n = 0; n < 13; ++n)
            if (const std::int32_t e = set_[static_cast<std::size_t>(d + offsets_[n])]; e >= 0)
              air_.unite(c, e, seal, nested);
        }
      for (std::size_t n = 0; n < level.size(); ++n) {
        const auto root = static_cast<std::size_t>(air_.find(level[n]));
        ++air_.above[root];
        air_.thick[root] = air_.thick[root] || level_thick[n];
      }
    }
    for (std::size_t c = 0; c < air_.parent.size(); ++c)
      if (air_.parent[c] == static_cast<std::int32_t>(c) && !air_.vented[c])
        seal(static_cast<std::int32_t>(c), air_.above[c], air_.top[c], air_.thick[c]);
  }

  FillResult result()
  {
    const auto largest_first = [](const AirPocket& a, const AirPocket& b) { return a.volume > b.volume; };
    std::sort(out_.pockets.begin(), out_.pockets.end(), largest_first);
    std::sort(out_.unreachable.begin(), out_.unreachable.end(), largest_first);
    std::sort(out_.nested.begin(), out_.nested.end(), largest_first);
    for (const AirPocket& p : out_.pockets) out_.trapped_volume += p.volume;
    return std::move(out_);
  }

private:
  std::uint8_t& state(Index d) { return state_[static_cast<std::size_t>(d)]; }

  Eigen::Vector3d centre(Index d) const
  {
    const Eigen::Vector3i v = g_.region_ijk(d);
    return r_.centre(v.x(), v.y(), v.z());
  }

  /// Fill on all six sides: not a crevice's voxel.
  bool thick_at(Index d) const
  {
    const std::array<Index, 6> faces{1, -1, g_.nx, -g_.nx, g_.nxy, -g_.nxy};
    return std::all_of(faces.begin(), faces.end(),
                       [&](Index o) { return is_fill(state_[static_cast<std::size_t>(d + o)]); });
  }

  std::vector<Index> voxels_of(const Port& p) const
  {
    std::vector<Index> found = port_voxels(r_, p);
    for (Index& d : found) {
      const Index i = d % r_.size.x(), j = (d / r_.size.x()) % r_.size.y(),
                  k = d / (static_cast<Index>(r_.size.x()) * r_.size.y());
      d = g_.at(i, j, k);
    }
    return found;
  }

  void flood(std::vector<Index>& q, std::uint8_t mark)
  {
    for (std::size_t n = 0; n < q.size(); ++n)
      for (const Index o : offsets_)
        if (const Index e = q[n] + o; state(e) == kInside) state(e) = mark, q.push_back(e);
  }

  /// A pocket is named by the voxel of its top level nearest the level's middle (within 8 voxels of
  /// it; else any voxel of that level: a long thin pocket's middle may be far from it); a vent can
  /// reach it when only mold lies above that voxel. One no thicker than two voxels that no vent can
  /// reach is a crevice.
  AirPocket pocket(std::int32_t root, Index voxels, const Top& top, bool thick)
  {
    const Index i = std::lround(top.i / static_cast<double>(top.n)),
                j = std::lround(top.j / static_cast<double>(top.n));
    Index at = nearest_in_level(
        r_, g_, top.k, i, j,
        [&](Index d) {
          return set_[static_cast<std::size_t>(d)] >= 0 && air_.find(set_[static_cast<std::size_t>(d)]) == root;
        },
        8);
    if (at < 0) at = top.any;
    bool ventable = true;
    for (Index e = at + g_.nxy; e < static_cast<Index>(state_.size()); e += g_.nxy)
      ventable = ventable && state_[static_cast<std::size_t>(e)] == kOutside;
    return AirPocket{static_cast<double>(voxels) * cell_, centre(at), ventable, !thick};
  }

  const VoxelRegion& r_;
  const Padded g_;
  const std::vector<Index> offsets_;
  const double cell_;
  std::vector<std::uint8_t> state_;
  std::vector<std::int32_t> set_; ///< per voxel: its air set in the sweep (≥ 0), or −2 − p for unreachable part p
  AirSets air_;
  FillResult out_;
};

} // namespace

FillResult simulate_fill(const VoxelRegion& r, const std::vector<Port>& sprues, const std::vector<Port>& vents)
{
  FillSweep sweep(r);
  sweep.reach_from(sprues);
  sweep.count_unreached();
  sweep.open_vents(vents);
  sweep.sweep_air();
  return sweep.result();
}

} // namespace fibermold

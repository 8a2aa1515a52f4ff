#include "molds/mold_block.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "core/elapsed.hpp"
#include "core/units.hpp"
#include "molds/mesh_boolean.hpp"
#include "molds/solids.hpp"

namespace fibermold {

namespace {

/// m: how deep a sprue's countersunk seat for the nozzle reaches into the block (at most half the wall).
constexpr double kSeatDepth = 2e-3;

/// Rotation taking `pull` to +z.
Eigen::Matrix3d to_local(const Eigen::Vector3d& pull)
{
  return Eigen::Quaterniond::FromTwoVectors(pull.normalized(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

SurfaceMesh transformed(SurfaceMesh m, const Eigen::Matrix3d& R)
{
  m.vertices = (m.vertices * R.transpose()).eval();
  return m;
}

/// Sites in the rim around the cavity, in the parting plane, inset by `inset` from the block's
/// sides: its corners, then its edge midpoints, then the edges' quarter points (16 in all).
std::vector<Eigen::Vector2d> rim_sites(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double inset)
{
  const double x0 = lo.x() + inset, x1 = hi.x() - inset, y0 = lo.y() + inset, y1 = hi.y() - inset;
  const auto x = [&](double t) { return x0 + t * (x1 - x0); };
  const auto y = [&](double t) { return y0 + t * (y1 - y0); };
  return {{x0, y0},      {x1, y1},      {x1, y0},      {x0, y1},      // corners
          {x(0.5), y0},  {x(0.5), y1},  {x0, y(0.5)},  {x1, y(0.5)},  // edge midpoints
          {x(0.25), y0}, {x(0.75), y1}, {x0, y(0.75)}, {x1, y(0.25)}, // quarter points
          {x(0.75), y0}, {x(0.25), y1}, {x0, y(0.25)}, {x1, y(0.75)}};
}

/// Distance in the parting plane from `s` to a segment ab.
double distance_to_segment(const Eigen::Vector2d& s, const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  const Eigen::Vector2d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((s - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (s - a - t * ab).norm();
}

/// Distance in the parting plane between segments ab and cd: 0 where they cross, else the least
/// of their ends' distances to the other.
double distance_between_segments(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                                 const Eigen::Vector2d& d)
{
  const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double c_side = cross(b - a, c - a), d_side = cross(b - a, d - a);
  const double a_side = cross(d - c, a - c), b_side = cross(d - c, b - c);
  if (c_side * d_side < 0 && a_side * b_side < 0) return 0;
  return std::min({distance_to_segment(a, c, d), distance_to_segment(b, c, d), distance_to_segment(c, a, b),
                   distance_to_segment(d, a, b)});
}

/// Appends b's vertices and faces to a (no boolean: for shells that do not touch).
void append(SurfaceMesh& a, const SurfaceMesh& b)
{
  const Eigen::Index n = a.num_vertices(), m = a.num_faces();
  a.vertices.conservativeResize(n + b.num_vertices(), 3);
  a.vertices.bottomRows(b.num_vertices()) = b.vertices;
  a.faces.conservativeResize(m + b.num_faces(), 3);
  a.faces.bottomRows(b.num_faces()) = b.faces.array() + static_cast<int>(n);
}

/// Moves every solid piece of `from` that does not reach the face of the block it belongs to
/// (height `base`, `below`: from is the lower half) over to `to`, which it touches at the plane.
/// A groove's rib hangs from the upper half; where the groove's bottom lies below the parting
/// plane, the cut leaves the rib's end as a loose piece of the lower half. The rib slides out of
/// its groove along pull with the upper half, so that is where it goes.
void reattach_loose_pieces(SurfaceMesh& from, SurfaceMesh& to, double base, bool below)
{
  std::vector<SurfaceMesh> shells = split_shells(from);
  if (shells.size() < 2) return;
  SurfaceMesh kept;
  kept.vertices.resize(0, 3);
  kept.faces.resize(0, 3);
  for (const SurfaceMesh& shell : shells) {
    const double reach = below ? shell.vertices.col(2).minCoeff() - base : base - shell.vertices.col(2).maxCoeff();
    if (signed_volume(shell) > 0 && reach > 1e-6) // 10 µm toward `to` where they share only an edge
      to = mesh_union_touching(to, shell, Eigen::Vector3d(0, 0, below ? 10e-6 : -10e-6));
    else
      append(kept, shell); // the block's piece, or a void inside it
  }
  from = std::move(kept);
}

SurfaceMesh key_solid(const Eigen::Vector3d& base, double radius, KeyShape shape, double sink)
{
  if (shape == KeyShape::hemisphere)
    return hemisphere_solid(base - Eigen::Vector3d(0, 0, sink), Eigen::Vector3d::UnitZ(), radius + sink, 32);
  return cone_solid(base - Eigen::Vector3d(0, 0, sink), base + Eigen::Vector3d(0, 0, radius), radius, radius / 2, 32);
}

/// A channel's passage through the block, seen along the pull.
struct Passage {
  Eigen::Vector2d a, b; ///< the channel's axis
  double radius;
};

/// Keys take the first sites (corners, then edge midpoints), screws the next free ones; a site
/// where a channel runs, or too close to a key or another screw, is left out.
std::pair<std::vector<Eigen::Vector2d>, std::vector<Eigen::Vector2d>>
key_and_screw_sites(const std::vector<Eigen::Vector2d>& sites, const std::vector<Passage>& passages,
                    const MoldBlockOptions& o)
{
  const double radius = o.key_diameter / 2, screw = o.screw_diameter / 2;
  const auto clear_of_channels = [&](const Eigen::Vector2d& s, double r) {
    return std::none_of(passages.begin(), passages.end(),
                        [&](const Passage& p) { return distance_to_segment(s, p.a, p.b) < r + p.radius + o.min_wall; });
  };
  std::vector<Eigen::Vector2d> keys, screws;
  for (int k = 0; k < std::min(o.keys, 8); ++k)
    if (clear_of_channels(sites[k], radius + o.key_clearance)) keys.push_back(sites[k]);
  for (std::size_t k = static_cast<std::size_t>(std::min(o.keys, 8));
       k < sites.size() && static_cast<int>(screws.size()) < o.screw_holes; ++k) {
    const bool clear_of_keys = std::all_of(keys.begin(), keys.end(), [&](const Eigen::Vector2d& key) {
      return (key - sites[k]).norm() >= radius + o.key_clearance + screw + o.min_wall;
    });
    const bool clear_of_screws = std::all_of(screws.begin(), screws.end(), [&](const Eigen::Vector2d& other) {
      return (other - sites[k]).norm() >= 2 * screw + o.min_wall;
    });
    if (clear_of_keys && clear_of_screws && clear_of_channels(sites[k], screw)) screws.push_back(sites[k]);
  }
  return {keys, screws};
}

/// Cuts the sprues and vents out of `block`, in the frame where the pull is +z (`R` takes the body's
/// frame there): each hole starts a little inside the cavity (its dip) so that the booleans meet no
/// tangent faces, and runs out through the block's bottom (a sprue from below) or top.
void cut_ports(SurfaceMesh& block, const Eigen::Matrix3d& R, const Ports& holes, const Eigen::Vector3d& box_lo,
               const Eigen::Vector3d& box_hi, const MoldBlockOptions& o, Mold& mold)
{
  const auto cut = [&](const Port& p, int segments) {
    const Eigen::Vector3d mouth = R * p.mouth, out = Eigen::Vector3d::UnitZ() * (p.upward ? 1 : -1);
    const double end = p.upward ? box_hi.z() + 1e-3 : box_lo.z() - 1e-3;
    block = mesh_difference(
        block, cylinder_solid(mouth - p.dip() * out, {mouth.x(), mouth.y(), end}, p.diameter / 2, segments));
    return p.mouth;
  };
  // A sprue's outer end is countersunk, a 45° seat for the dispenser's nozzle that tells it from the
  // vents on the printed part, kSeatDepth deep where the holes beside it on the same face leave room
  // (min_wall between the seat and them), shallower where not, and none under 0.5 mm. The cone crosses
  // the hole's wall transversally: one meeting the cylinder along a circle would leave CGAL tangent faces.
  const auto seat_depth = [&](const Port& p) {
    double room = std::min(kSeatDepth, o.wall / 2);
    const Eigen::Vector2d at = (R * p.mouth).head<2>();
    for (const std::vector<Port>* others : {&holes.sprues, &holes.vents})
      for (const Port& q : *others)
        if (&q != &p && q.upward == p.upward)
          room = std::min(room, ((R * q.mouth).head<2>() - at).norm() - q.diameter / 2 - o.min_wall - p.diameter / 2);
    return room;
  };
  const auto countersink = [&](const Port& p) {
    const double seat = seat_depth(p);
    if (seat < 0.5e-3) return;
    const Eigen::Vector3d mouth = R * p.mouth;
    const double face = p.upward ? box_hi.z() : box_lo.z(), out = p.upward ? 1 : -1, r = p.diameter / 2;
    const Eigen::Vector3d inner(mouth.x(), mouth.y(), face - out * (seat + 0.5e-3));
    block = mesh_difference(
        block, cone_solid(inner, {mouth.x(), mouth.y(), face + out * 1e-3}, r - 0.5e-3, r + seat + 1e-3, 20));
  };
  for (const Port& p : holes.sprues) {
    mold.sprues.push_back(cut(p, 24));
    countersink(p);
  }
  for (const Port& p : holes.vents) mold.vents.push_back(cut(p, 16));
}

/// Engraves one half (in the frame where the pull is +z; `lower`: the half under the plane at height
/// h): "IN" beside each sprue that opens through its outer end face, then its label on its longest
/// side face that takes it, else that end face. What fits nowhere is left out and said in `part`.
void label_half(SurfaceMesh& half, bool lower, const Eigen::Vector3d& box_lo, const Eigen::Vector3d& box_hi, double h,
                const Ports& holes, const Eigen::Matrix3d& R, const MoldBlockOptions& o, const PartLabels& labels,
                const std::string& shot, MoldPart& part)
{
  const LabelStyle& style = labels.style;
  const double z0 = lower ? box_lo.z() : h, z1 = lower ? h : box_hi.z(), zm = (z0 + z1) / 2;
  const double end = lower ? box_lo.z() : box_hi.z();
  const Eigen::Vector3d mid = (box_lo + box_hi) / 2, span = box_hi - box_lo;
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
  const LabelFace end_face{"end", {mid.x(), mid.y(), end}, lower ? -Z : Z, Y, {span.x(), span.y()}, {}};
  std::vector<PlacedLabel> placed;
  LabelStyle mark = style;
  mark.max_height = style.min_height;
  for (const Port& p : holes.sprues) {
    if (p.upward == lower) continue;
    const Eigen::Vector3d mouth = R * p.mouth, at(mouth.x(), mouth.y(), end);
    // A square around the mouth, room for the seat and a mark on any side of it.
    const double side = p.diameter + 2 * kSeatDepth + 4 * (mark.max_height + o.min_wall + style.depth);
    if (auto l =
            place_label(half, {"IN"}, {{"end", at, end_face.normal, Y, {side, side}, at}}, mark, o.min_wall, placed))
      placed.push_back(*l);
    else
      part.unlabelled.push_back(fmt::format("no room for \"IN\" beside the sprue at {}", format_mm(p.mouth)));
  }
  std::vector<LabelFace> faces{{"side", {mid.x(), box_lo.y(), zm}, -Y, Z, {span.x(), z1 - z0}, {}},
                               {"side", {mid.x(), box_hi.y(), zm}, Y, Z, {span.x(), z1 - z0}, {}},
                               {"side", {box_lo.x(), mid.y(), zm}, -X, Z, {span.y(), z1 - z0}, {}},
                               {"side", {box_hi.x(), mid.y(), zm}, X, Z, {span.y(), z1 - z0}, {}}};
  std::stable_sort(faces.begin(), faces.end(),
                   [](const LabelFace& a, const LabelFace& b) { return a.size.x() > b.size.x(); });
  faces.push_back(end_face);
  const std::vector<std::string> texts = part_label_texts(labels.design, shot, lower);
  if (auto l = place_label(half, texts, faces, style, o.min_wall, placed))
    placed.insert(placed.begin(), *l);
  else
    part.unlabelled.push_back(fmt::format("no room for \"{}\" ({:.0f} mm capitals or more) on any side or end face",
                                          texts.back(), style.min_height / units::mm));
  try {
    half = engrave(half, placed, style, o.min_wall);
  } catch (const std::exception& e) {
    part.unlabelled.push_back(fmt::format("labels left out: {}", e.what()));
    return;
  }
  for (PlacedLabel& l : placed) { // to the body's frame
    l.centre = R.transpose() * l.centre;
    l.normal = R.transpose() * l.normal;
    l.up = R.transpose() * l.up;
    part.labels.push_back(l);
  }
}

} // namespace

std::vector<std::string> part_label_texts(const std::string& design, const std::string& shot, bool lower)
{
  const std::string n = shot.starts_with("shot") ? shot.substr(4) : shot;
  const std::string half = lower ? "LOWER" : "UPPER", brief = "S" + n + (lower ? "L" : "U");
  std::string name; // as cut
  for (const char c : design) name += label_character(c);
  std::vector<std::string> texts;
  if (!name.empty()) texts = {name + " S" + n + " " + half, name + " " + brief};
  texts.push_back("S" + n + " " + half);
  texts.push_back(brief);
  return texts;
}

Eigen::Vector3d block_margin(const MoldBlockOptions& o)
{
  const double key_room = o.keys > 0 ? o.key_diameter + 2 * o.key_clearance + 2 * o.min_wall : 0;
  const double screw_room = o.screw_holes > 0 ? o.screw_diameter + 2 * o.min_wall : 0;
  const double side = std::max({o.wall, key_room, screw_room});
  return {side, side, o.wall};
}

Eigen::Vector3d least_half_size(const SurfaceMesh& cavity, const Eigen::Vector3d& pull, const MoldBlockOptions& o)
{
  const Eigen::Matrix3d R = to_local(pull);
  const SurfaceMesh local = transformed(cavity, R);
  const Eigen::Vector3d block = local.vertices.colwise().maxCoeff().transpose() -
                                local.vertices.colwise().minCoeff().transpose() + 2 * block_margin(o);
  // The half is a box of the block's width and depth and at least half its height in the pull's frame; the parts
  // are checked in the design's frame, where that box's extent along axis i is Σ_j |Rᵀ_ij| · size_j (a pull off the
  // design's axes turns it: a 260 mm bar along (1, 0, -1) pulled along (1, 0, 1) has halves 205.6 mm across).
  return R.transpose().cwiseAbs() * Eigen::Vector3d(block.x(), block.y(), block.z() / 2);
}

Mold make_mold(const SurfaceMesh& cavity_world, const Parting& parting, const std::vector<Channel>& channels,
               const MoldBlockOptions& o, const std::string& shot, const Ports* ports, const PartLabels* labels)
{
  const Eigen::Matrix3d R = to_local(parting.normal);
  const SurfaceMesh cavity = transformed(cavity_world, R);
  const double h = (R * parting.point).z();
  const Eigen::Vector3d lo = cavity.vertices.colwise().minCoeff(), hi = cavity.vertices.colwise().maxCoeff();
  const Eigen::Vector3d grow = block_margin(o);
  const double side = grow.x();
  const Eigen::Vector3d box_lo = lo - grow, box_hi = hi + grow;
  SurfaceMesh block = mesh_difference(box_solid(box_lo, box_hi), cavity);

  Mold mold;
  const Ports own =
      ports ? Ports{}
            : cavity_ports(cavity_world, parting.normal, o.sprue_diameter, o.vents, o.vent_diameter, o.min_wall, shot);
  const Ports& holes = ports ? *ports : own;
  cut_ports(block, R, holes, box_lo, box_hi, o, mold);
  const double reach = (box_hi - box_lo).norm();
  std::vector<Passage> passages;
  std::vector<double> heights; // each channel's height when laid parallel to the plane, else NaN
  // Channels run parallel to the parting plane (one crossing it at an angle would leave a wedge of
  // mold thinner than any wall); one that starts within its radius + min_wall of the plane is moved
  // onto it, so that each half holds half the tube and lets go of it when pulled.
  for (const Channel& c : channels) {
    Eigen::Vector3d a = R * c.start, d = R * c.direction;
    const double vertical = d.z();
    d.z() = 0;
    if (d.norm() < 1e-6)
      d = Eigen::Vector3d(0, 0, vertical < 0 ? -1 : 1); // straight up or down: out through the top or bottom
    d.normalize();
    if (d.z() == 0 && std::abs(a.z() - h) < c.diameter / 2 + o.min_wall) a.z() = h;
    const bool stepped = c.through_diameter > 0 && c.through_diameter < c.diameter && c.socket < reach;
    block = mesh_difference(block, cylinder_solid(a, a + (stepped ? c.socket : reach) * d, c.diameter / 2, 24));
    // The hole starts a little inside the socket, and has other facets than the socket (20, not
    // 24): coaxial prisms with vertices on the same rays leave CGAL's cut with crossing faces.
    if (stepped)
      block = mesh_difference(
          block, cylinder_solid(a + (c.socket - c.diameter / 4) * d, a + reach * d, c.through_diameter / 2, 20));
    passages.push_back({a.head<2>(), (a + reach * d).head<2>(), c.diameter / 2});
    heights.push_back(d.z() == 0 ? a.z() : NAN);
  }
  // Two channels laid parallel to the plane, at heights z and z': their axes are sqrt(Δz² + (their
  // distance in the plane)²) apart (each at its socket's width all along, as the keys see them).
  for (std::size_t i = 0; i < passages.size(); ++i)
    for (std::size_t j = i + 1; j < passages.size(); ++j) {
      if (std::isnan(heights[i]) || std::isnan(heights[j])) continue;
      const Passage &p = passages[i], &q = passages[j];
      const double wall =
          std::hypot(heights[i] - heights[j], distance_between_segments(p.a, p.b, q.a, q.b)) - p.radius - q.radius;
      if (wall < o.min_wall) mold.close_channels.push_back({static_cast<int>(i), static_cast<int>(j), wall});
    }

  const double radius = o.key_diameter / 2, sink = 0.5e-3, screw = o.screw_diameter / 2;
  const auto [keys, screws] = key_and_screw_sites(rim_sites(box_lo, box_hi, side / 2), passages, o);
  for (const Eigen::Vector2d& s : screws) {
    block = mesh_difference(
        block, cylinder_solid({s.x(), s.y(), box_lo.z() - 1e-3}, {s.x(), s.y(), box_hi.z() + 1e-3}, screw, 24));
    mold.screws.push_back(R.transpose() * Eigen::Vector3d(s.x(), s.y(), h));
  }

  auto [lower, upper] = split_by_plane(block, {0, 0, h}, Eigen::Vector3d::UnitZ());
  reattach_loose_pieces(lower, upper, box_lo.z(), true);
  reattach_loose_pieces(upper, lower, box_hi.z(), false);
  for (const Eigen::Vector2d& s : keys) {
    const Eigen::Vector3d base(s.x(), s.y(), h);
    lower = mesh_union(lower, key_solid(base, radius, o.key_shape, sink));
    upper = mesh_difference(upper, key_solid(base, radius + o.key_clearance, o.key_shape, sink)); // clearance all round
    mold.keys.push_back(R.transpose() * base);
  }
  // Back to the body's frame. Unless R is the identity, the rotation rounds every vertex, and a
  // corefinement's sliver can come out with its three corners on one line (a 10-sided arm parted
  // across y: two such faces in shot 1's upper half).
  const auto back = [&](SurfaceMesh part) {
    return R.isIdentity(0) ? part : without_degenerate_faces(transformed(std::move(part), R.transpose()));
  };
  MoldPart lower_part{shot + "-lower", {}, {}, {}}, upper_part{shot + "-upper", {}, {}, {}};
  if (labels) {
    const auto started = std::chrono::steady_clock::now();
    label_half(lower, true, box_lo, box_hi, h, holes, R, o, *labels, shot, lower_part);
    label_half(upper, false, box_lo, box_hi, h, holes, R, o, *labels, shot, upper_part);
    mold.label_seconds = since(started);
  }
  lower_part.mesh = back(std::move(lower));
  upper_part.mesh = back(std::move(upper));
  mold.parts.push_back(std::move(lower_part));
  mold.parts.push_back(std::move(upper_part));
  return mold;
}

} // namespace fibermold

#include "molds/part_label.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <unordered_map>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/intersections.h>
#include <Eigen/Geometry>
#include <fmt/format.h>

extern "C" {
#include <hersheyfont.h>
}

#include "core/units.hpp"
#include "molds/mesh_boolean.hpp"
#include "molds/part_checks.hpp"
#include "molds/solids.hpp"

namespace fibermold {

namespace {

/// The Hershey simplex roman font of Debian's hershey-fonts-data: one stroke per line of a letter.
constexpr const char* kFontFile = "/usr/share/hershey-fonts/futural.jhf";
/// The font's units per capital height (its capitals run from y = 0 to 21).
constexpr double kCapUnits = 21;
/// m: how far the engraving's solid reaches out of the face, so that the boolean meets no coplanar faces.
constexpr double kAbove = 0.5e-3;
/// Gaps between grooves narrower than this times min_wall are cut too (the closing's diameter).
constexpr double kLandFactor = 1.1;
/// m: a point within this of a face's plane lies on it (the blocks' faces are exact there).
constexpr double kOnPlane = 1e-7;

struct Glyph {
  double advance = 0;                              ///< font units
  std::vector<std::vector<Eigen::Vector2d>> paths; ///< font units
};

/// The font's printable ASCII glyphs, read once from the installed font file.
const std::array<Glyph, 128>& font()
{
  static const std::array<Glyph, 128> glyphs = [] {
    if (!std::filesystem::exists(kFontFile))
      throw std::runtime_error(fmt::format("the Hershey font {} for the parts' labels is missing: install Debian's "
                                           "hershey-fonts-data (scripts/setup does)",
                                           kFontFile));
    hershey_font* f = hershey_jhf_font_load(kFontFile);
    if (!f) throw std::runtime_error(fmt::format("cannot read the Hershey font {}", kFontFile));
    std::array<Glyph, 128> out;
    for (int c = 32; c < 127; ++c) {
      const hershey_glyph* g = hershey_font_glyph(f, static_cast<unsigned char>(c));
      out[c].advance = g->width;
      for (const hershey_path* p = g->paths; p; p = p->next) {
        std::vector<Eigen::Vector2d> path;
        for (int k = 0; k < p->nverts; ++k) path.emplace_back(p->verts[k].x, p->verts[k].y);
        out[c].paths.push_back(std::move(path));
      }
    }
    hershey_font_free(f);
    return out;
  }();
  return glyphs;
}

double segment_distance(const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  const Eigen::Vector2d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (q - a - t * ab).norm();
}

/// Whether segments ab and cd cross or touch.
bool segments_meet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d)
{
  const auto side = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
    const double z = (q - p).x() * (r - p).y() - (q - p).y() * (r - p).x();
    return (z > 0) - (z < 0);
  };
  return side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0;
}

/// The least distance between the strokes `a` and the strokes `b` moved by `shift` (HUGE_VAL when either is empty).
double strokes_distance(const std::vector<std::vector<Eigen::Vector2d>>& a,
                        const std::vector<std::vector<Eigen::Vector2d>>& b, const Eigen::Vector2d& shift)
{
  double least = HUGE_VAL;
  for (const auto& p : a)
    for (const auto& q : b)
      for (std::size_t i = 0; i < p.size(); ++i)
        for (std::size_t j = 0; j < q.size(); ++j) {
          const Eigen::Vector2d a0 = p[i], a1 = p[std::min(i + 1, p.size() - 1)];
          const Eigen::Vector2d b0 = q[j] + shift, b1 = q[std::min(j + 1, q.size() - 1)] + shift;
          if (segments_meet(a0, a1, b0, b1)) return 0;
          least = std::min({least, segment_distance(a0, b0, b1), segment_distance(a1, b0, b1),
                            segment_distance(b0, a0, a1), segment_distance(b1, a0, a1)});
        }
  return least;
}

/// A sampled field on a grid of square pixels: f(i, j) at origin + pixel · (i, j).
struct Grid {
  Eigen::Vector2d origin;
  double pixel = 0;
  int nx = 0, ny = 0;
  std::vector<double> f;
  double& at(int i, int j) { return f[static_cast<std::size_t>(j) * nx + i]; }
  double at(int i, int j) const { return f[static_cast<std::size_t>(j) * nx + i]; }
  Eigen::Vector2d point(int i, int j) const { return origin + pixel * Eigen::Vector2d(i, j); }
};

/// The signed distance (negative inside) of the grooves: within stroke/2 of a stroke, or in a gap
/// narrower than 2 · closing between them (a morphological closing: the points `closing` deep in the
/// strokes grown by `closing`).
Grid groove_field(const std::vector<std::vector<Eigen::Vector2d>>& strokes, double stroke, double closing,
                  const Eigen::Vector2d& lo, const Eigen::Vector2d& hi)
{
  Grid g;
  g.pixel = stroke / 16;
  const double r = stroke / 2, grown = r + closing, margin = grown + 3 * g.pixel;
  g.origin = lo - Eigen::Vector2d::Constant(margin);
  g.nx = static_cast<int>(std::ceil((hi.x() - lo.x() + 2 * margin) / g.pixel)) + 1;
  g.ny = static_cast<int>(std::ceil((hi.y() - lo.y() + 2 * margin) / g.pixel)) + 1;
  g.f.assign(static_cast<std::size_t>(g.nx) * g.ny, HUGE_VAL); // first the distance to the strokes
  const auto index = [&](double v, double o) { return static_cast<int>(std::floor((v - o) / g.pixel)); };
  for (const auto& path : strokes)
    for (std::size_t k = 0; k < path.size(); ++k) {
      const Eigen::Vector2d a = path[k], b = path[std::min(k + 1, path.size() - 1)];
      const int i0 = std::max(0, index(std::min(a.x(), b.x()) - grown - g.pixel, g.origin.x()));
      const int i1 = std::min(g.nx - 1, index(std::max(a.x(), b.x()) + grown + g.pixel, g.origin.x()) + 1);
      const int j0 = std::max(0, index(std::min(a.y(), b.y()) - grown - g.pixel, g.origin.y()));
      const int j1 = std::min(g.ny - 1, index(std::max(a.y(), b.y()) + grown + g.pixel, g.origin.y()) + 1);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) g.at(i, j) = std::min(g.at(i, j), segment_distance(g.point(i, j), a, b));
    }
  // The closing: a point of the grown strokes `closing` from every point outside them is inside.
  const int reach = static_cast<int>(std::ceil(closing / g.pixel)) + 1;
  std::vector<double> out(g.f.size());
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double d = g.at(i, j);
      double f = d - r;
      if (f > 0 && d <= grown) {
        double clear = HUGE_VAL; // to the nearest pixel outside the grown strokes, less half a pixel
        for (int jj = std::max(0, j - reach); jj <= std::min(g.ny - 1, j + reach); ++jj)
          for (int ii = std::max(0, i - reach); ii <= std::min(g.nx - 1, i + reach); ++ii)
            if (g.at(ii, jj) > grown) clear = std::min(clear, g.pixel * std::hypot(ii - i, jj - j));
        f = std::min(f, closing - (clear - g.pixel / 2));
      }
      out[static_cast<std::size_t>(j) * g.nx + i] = f < 0 ? f : std::max(f, 1e-3 * g.pixel); // no node on the line
    }
  g.f = std::move(out);
  return g;
}

/// The closed outlines where the field is zero (marching squares), inside on their left.
std::vector<std::vector<Eigen::Vector2d>> contours(const Grid& g)
{
  const auto inside = [&](int i, int j) { return g.at(i, j) < 0; };
  // Crossings on the grid's edges: 2 (j nx + i) the edge from (i, j) along x, + 1 along y.
  std::unordered_map<long, long> next;
  std::unordered_map<long, Eigen::Vector2d> where;
  const auto crossing = [&](int i, int j, bool along_y) {
    const long id = 2L * (static_cast<long>(j) * g.nx + i) + (along_y ? 1 : 0);
    const int i2 = along_y ? i : i + 1, j2 = along_y ? j + 1 : j;
    const double a = g.at(i, j), b = g.at(i2, j2), t = std::clamp(a / (a - b), 1e-3, 1 - 1e-3);
    where.emplace(id, (1 - t) * g.point(i, j) + t * g.point(i2, j2));
    return id;
  };
  for (int j = 0; j + 1 < g.ny; ++j)
    for (int i = 0; i + 1 < g.nx; ++i) {
      const std::array<std::array<int, 2>, 4> c{{{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}}}; // counter-clockwise
      const std::array<std::array<int, 3>, 4> edge{{{i, j, 0}, {i + 1, j, 1}, {i, j + 1, 0}, {i, j, 1}}};
      std::array<bool, 4> in{};
      for (int k = 0; k < 4; ++k) in[k] = inside(c[k][0], c[k][1]);
      const auto id = [&](int k) { return crossing(edge[k][0], edge[k][1], edge[k][2] == 1); };
      const auto exits = [&](int k) { return in[k] && !in[(k + 1) % 4]; };
      const auto enters = [&](int k) { return !in[k] && in[(k + 1) % 4]; };
      int n = 0;
      for (int k = 0; k < 4; ++k) n += exits(k);
      if (n == 1) {
        int from = 0, to = 0;
        for (int k = 0; k < 4; ++k) {
          if (exits(k)) from = k;
          if (enters(k)) to = k;
        }
        next[id(from)] = id(to);
      } else if (n == 2) { // a saddle: the centre decides whether the insides join
        const bool joined = g.at(i, j) + g.at(i + 1, j) + g.at(i + 1, j + 1) + g.at(i, j + 1) < 0;
        for (int k = 0; k < 4; ++k)
          if (exits(k)) next[id(k)] = id((k + (joined ? 1 : 3)) % 4);
      }
    }
  std::vector<long> starts; // in order, so that the same text gives the same outlines
  for (const auto& [start, unused] : next) starts.push_back(start);
  std::sort(starts.begin(), starts.end());
  std::vector<std::vector<Eigen::Vector2d>> loops;
  std::unordered_map<long, bool> done;
  for (const long start : starts) {
    if (done[start]) continue;
    std::vector<Eigen::Vector2d> loop;
    for (long at = start; !done[at]; at = next.at(at)) {
      done[at] = true;
      loop.push_back(where.at(at));
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

/// The loop with the points that lie within `tolerance` of the line between kept ones left out
/// (Douglas-Peucker, from its first point and the point farthest from it).
std::vector<Eigen::Vector2d> simplified(const std::vector<Eigen::Vector2d>& loop, double tolerance)
{
  const std::size_t n = loop.size();
  if (n < 4) return loop;
  std::size_t far = 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((loop[k] - loop[0]).squaredNorm() > (loop[far] - loop[0]).squaredNorm()) far = k;
  std::vector<bool> keep(n, false);
  keep[0] = keep[far] = true;
  std::vector<std::pair<std::size_t, std::size_t>> todo{{0, far}, {far, n}}; // index n is point 0 again
  while (!todo.empty()) {
    const auto [a, b] = todo.back();
    todo.pop_back();
    double worst = tolerance;
    std::size_t split = a;
    for (std::size_t k = a + 1; k < b; ++k)
      if (const double d = segment_distance(loop[k], loop[a], loop[b % n]); d > worst) worst = d, split = k;
    if (split == a) continue;
    keep[split] = true;
    todo.push_back({a, split});
    todo.push_back({split, b});
  }
  std::vector<Eigen::Vector2d> out;
  for (std::size_t k = 0; k < n; ++k)
    if (keep[k]) out.push_back(loop[k]);
  return out;
}

double signed_area(const std::vector<Eigen::Vector2d>& loop)
{
  double a = 0;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Eigen::Vector2d &p = loop[k], &q = loop[(k + 1) % loop.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return a / 2;
}

/// The strokes' box in font units per capital height: lower corner and size.
std::pair<Eigen::Vector2d, Eigen::Vector2d> unit_box(const std::vector<std::vector<Eigen::Vector2d>>& strokes)
{
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(HUGE_VAL), hi = -lo;
  for (const auto& path : strokes)
    for (const Eigen::Vector2d& p : path) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (!(lo.array() <= hi.array()).all()) return {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  return {lo, hi - lo};
}

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

/// The triangles (of a mesh or a label's box) near a face, in the face's frame: x along the reading
/// direction, y up, z out of the part, from the face's centre.
struct FaceFrame {
  Eigen::Vector3d centre, right, up, normal;
  Eigen::Vector3d local(const Eigen::Vector3d& p) const
  {
    const Eigen::Vector3d d = p - centre;
    return {d.dot(right), d.dot(up), d.dot(normal)};
  }
  Eigen::Vector3d world(const Eigen::Vector3d& p) const { return centre + p.x() * right + p.y() * up + p.z() * normal; }
};

FaceFrame frame_of(const Eigen::Vector3d& centre, const Eigen::Vector3d& normal, const Eigen::Vector3d& up)
{
  const Eigen::Vector3d n = normal.normalized(), u = (up - up.dot(n) * n).normalized();
  return {centre, u.cross(n), u, n};
}

struct Obstacle {
  Kernel::Triangle_3 triangle;
  CGAL::Bbox_3 box;
};

/// What a label on a face must keep clear of, and the face's own triangles (on its plane, facing out).
struct FaceSurroundings {
  std::vector<Obstacle> obstacles;
  std::vector<std::array<Eigen::Vector2d, 3>> face;
};

FaceSurroundings surroundings(const SurfaceMesh& part, const FaceFrame& frame, const Eigen::Vector2d& size,
                              double reach, double below, const std::vector<PlacedLabel>& placed)
{
  FaceSurroundings s;
  const auto add = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, bool own) {
    const Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
    if (hi.x() < -size.x() / 2 - reach || lo.x() > size.x() / 2 + reach || hi.y() < -size.y() / 2 - reach ||
        lo.y() > size.y() / 2 + reach || hi.z() < -below || lo.z() > reach)
      return;
    const bool on_plane = std::abs(a.z()) < kOnPlane && std::abs(b.z()) < kOnPlane && std::abs(c.z()) < kOnPlane;
    const double facing = (b - a).cross(c - a).z();
    if (own && on_plane && facing > 0) {
      s.face.push_back({a.head<2>(), b.head<2>(), c.head<2>()});
      return;
    }
    const Kernel::Triangle_3 t({a.x(), a.y(), a.z()}, {b.x(), b.y(), b.z()}, {c.x(), c.y(), c.z()});
    if (!t.is_degenerate()) s.obstacles.push_back({t, t.bbox()});
  };
  for (Eigen::Index f = 0; f < part.num_faces(); ++f)
    add(frame.local(part.vertices.row(part.faces(f, 0))), frame.local(part.vertices.row(part.faces(f, 1))),
        frame.local(part.vertices.row(part.faces(f, 2))), true);
  for (const PlacedLabel& l : placed) { // the groove's box, as 12 triangles
    const FaceFrame lf = frame_of(l.centre, l.normal, l.up);
    std::array<Eigen::Vector3d, 8> c;
    for (int k = 0; k < 8; ++k)
      c[k] = frame.local(
          lf.world({(k & 1 ? 0.5 : -0.5) * l.extent.x(), (k & 2 ? 0.5 : -0.5) * l.extent.y(), k & 4 ? 0.0 : -l.depth}));
    for (const auto& [a, b, d] : std::array<std::array<int, 3>, 12>{{{0, 1, 3},
                                                                     {0, 3, 2},
                                                                     {4, 5, 7},
                                                                     {4, 7, 6},
                                                                     {0, 1, 5},
                                                                     {0, 5, 4},
                                                                     {2, 3, 7},
                                                                     {2, 7, 6},
                                                                     {0, 2, 6},
                                                                     {0, 6, 4},
                                                                     {1, 3, 7},
                                                                     {1, 7, 5}}})
      add(c[a], c[b], c[d], false);
  }
  return s;
}

bool on_face(const FaceSurroundings& s, const Eigen::Vector2d& q)
{
  const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
  return std::any_of(s.face.begin(), s.face.end(), [&](const std::array<Eigen::Vector2d, 3>& t) {
    return cross(t[1] - t[0], q - t[0]) >= 0 && cross(t[2] - t[1], q - t[1]) >= 0 && cross(t[0] - t[2], q - t[2]) >= 0;
  });
}

/// Whether a groove box of `extent` centred at `at` on the face keeps `clear` from everything but
/// the face (and `below` under its floor), and lies on the face.
bool fits_at(const FaceSurroundings& s, const Eigen::Vector2d& at, const Eigen::Vector2d& extent, double clear,
             double below)
{
  const Eigen::Vector2d lo = at - extent / 2, hi = at + extent / 2;
  for (const Eigen::Vector2d& q : {at, lo, hi, Eigen::Vector2d(lo.x(), hi.y()), Eigen::Vector2d(hi.x(), lo.y())})
    if (!on_face(s, q)) return false;
  const Kernel::Iso_cuboid_3 box({lo.x() - clear, lo.y() - clear, -below}, {hi.x() + clear, hi.y() + clear, clear});
  const CGAL::Bbox_3 bbox = box.bbox();
  return std::none_of(s.obstacles.begin(), s.obstacles.end(), [&](const Obstacle& o) {
    return CGAL::do_overlap(o.box, bbox) && CGAL::do_intersect(o.triangle, box);
  });
}

/// Centres for a box of `extent` on a face of `size`, `clear` from its edges, nearest `near` first
/// (at most 21 along each side).
std::vector<Eigen::Vector2d> candidate_centres(const Eigen::Vector2d& size, const Eigen::Vector2d& extent, double clear,
                                               const Eigen::Vector2d& near)
{
  const Eigen::Vector2d room = (size - extent) / 2 - Eigen::Vector2d::Constant(clear);
  if ((room.array() < 0).any()) return {};
  std::vector<Eigen::Vector2d> out;
  const auto steps = [](double r) { return std::min(10, static_cast<int>(std::floor(r / units::mm))); };
  const int nx = steps(room.x()), ny = steps(room.y());
  for (int j = -ny; j <= ny; ++j)
    for (int i = -nx; i <= nx; ++i) out.emplace_back(nx ? room.x() * i / nx : 0.0, ny ? room.y() * j / ny : 0.0);
  std::stable_sort(out.begin(), out.end(), [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - near).squaredNorm() < (b - near).squaredNorm();
  });
  return out;
}

} // namespace

/// Whether the label's lands print: cut into a plain slab, the part checks find no wall under min_wall
/// (a pinch between two strokes' ends that the closing leaves, such as a G's mouth at small heights).
bool lands_print(const std::string& text, double height, const LabelStyle& style, double min_wall)
{
  const PlacedLabel l{text,
                      "test",
                      Eigen::Vector3d::Zero(),
                      Eigen::Vector3d::UnitZ(),
                      Eigen::Vector3d::UnitY(),
                      height,
                      Eigen::Vector2d::Zero(),
                      style.depth};
  const Eigen::Vector2d size = unit_box(text_strokes(text, height, style.stroke + kLandFactor * min_wall)).second;
  const double margin = 2 * (min_wall + style.depth) + style.stroke;
  const SurfaceMesh slab = box_solid({-size.x() / 2 - margin, -size.y() / 2 - margin, -3 * (min_wall + style.depth)},
                                     {size.x() / 2 + margin, size.y() / 2 + margin, 0});
  try {
    const PartCheck c = check_part(engrave(slab, {l}, style, min_wall), min_wall, Eigen::Vector3d::Constant(HUGE_VAL));
    return c.ok();
  } catch (const std::exception&) {
    return false;
  }
}

std::vector<double> label_heights(const LabelStyle& style)
{
  std::vector<double> out;
  const int steps = static_cast<int>(std::floor((style.max_height - style.min_height) / style.height_step + 1e-9));
  for (int k = 0; k <= steps; ++k) out.push_back(style.max_height - k * style.height_step);
  return out;
}

char label_character(char c)
{
  const auto u = static_cast<unsigned char>(c);
  return u < 32 || u > 126 ? '?' : static_cast<char>(std::toupper(u));
}

std::vector<std::vector<Eigen::Vector2d>> text_strokes(const std::string& text, double height, double gap)
{
  const std::array<Glyph, 128>& glyphs = font();
  const double scale = height / kCapUnits;
  std::vector<std::vector<Eigen::Vector2d>> strokes, previous;
  double x = 0; // m, where the letter's box starts
  for (const char ch : text) {
    const int c = label_character(ch);
    std::vector<std::vector<Eigen::Vector2d>> letter;
    for (const auto& path : glyphs[c].paths) {
      std::vector<Eigen::Vector2d> p;
      for (const Eigen::Vector2d& v : path) p.push_back(scale * v);
      letter.push_back(std::move(p));
    }
    // The letter moves right until its strokes keep `gap` from the letter before it.
    for (int k = 0; k < 20; ++k) {
      const double d = strokes_distance(previous, letter, Eigen::Vector2d(x, 0));
      if (d >= gap - 1e-9) break;
      x += gap - d + 1e-6;
    }
    for (auto& path : letter)
      for (Eigen::Vector2d& v : path) v.x() += x;
    if (!letter.empty()) previous = letter;
    strokes.insert(strokes.end(), letter.begin(), letter.end());
    x += scale * glyphs[c].advance;
  }
  return strokes;
}

std::vector<std::vector<Eigen::Vector2d>> text_outlines(const std::string& text, double height, double stroke,
                                                        double closing)
{
  std::vector<std::vector<Eigen::Vector2d>> strokes = text_strokes(text, height, stroke + 2 * closing);
  const auto [lo, size] = unit_box(strokes);
  if (strokes.empty()) return {};
  const Eigen::Vector2d mid = lo + size / 2;
  for (auto& path : strokes)
    for (Eigen::Vector2d& p : path) p -= mid;
  const Grid g = groove_field(strokes, stroke, closing, -size / 2, size / 2);
  std::vector<std::vector<Eigen::Vector2d>> out;
  for (const auto& loop : contours(g)) {
    std::vector<Eigen::Vector2d> s = simplified(loop, g.pixel / 5);
    if (s.size() >= 3 && std::abs(signed_area(s)) > g.pixel * g.pixel) out.push_back(std::move(s));
  }
  return out;
}

double outlines_area(const std::vector<std::vector<Eigen::Vector2d>>& outlines)
{
  double a = 0;
  for (const auto& loop : outlines) a += signed_area(loop);
  return a;
}

std::optional<PlacedLabel> place_label(const SurfaceMesh& part, const std::vector<std::string>& texts,
                                       const std::vector<LabelFace>& faces, const LabelStyle& style, double min_wall,
                                       const std::vector<PlacedLabel>& placed)
{
  const double clear = min_wall + style.depth, below = style.depth + min_wall;
  const double gap = style.stroke + kLandFactor * min_wall;
  std::map<std::pair<std::string, long>, bool> prints;
  const std::vector<double> heights = label_heights(style);
  for (const std::string& text : texts) {
    if (unit_box(text_strokes(text, 1.0, 0)).second.isZero()) continue;
    for (const LabelFace& face : faces) {
      const FaceFrame frame = frame_of(face.centre, face.normal, face.up);
      const FaceSurroundings s = surroundings(part, frame, face.size, clear, below, placed);
      const Eigen::Vector2d near = face.near ? frame.local(*face.near).head<2>().eval() : Eigen::Vector2d::Zero();
      for (const double h : heights) {
        const Eigen::Vector2d extent =
            unit_box(text_strokes(text, h, gap)).second + Eigen::Vector2d::Constant(style.stroke);
        for (const Eigen::Vector2d& at : candidate_centres(face.size, extent, clear, near)) {
          if (!fits_at(s, at, extent, clear, below)) continue;
          // Whether its lands print: checked once per text and height, where it first fits.
          const auto key = std::make_pair(text, static_cast<long>(std::lround(1000 * h / units::mm)));
          if (!prints.count(key)) prints[key] = lands_print(text, h, style, min_wall);
          if (!prints[key]) break;
          return PlacedLabel{text,   face.name,  frame.world({at.x(), at.y(), 0}), frame.normal, frame.up, h,
                             extent, style.depth};
        }
      }
    }
  }
  return std::nullopt;
}

SurfaceMesh label_solid(const PlacedLabel& label, const LabelStyle& style, double min_wall)
{
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
  using Fb =
      CGAL::Constrained_triangulation_face_base_2<Kernel, CGAL::Triangulation_face_base_with_info_2<int, Kernel>>;
  using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, CGAL::Triangulation_data_structure_2<Vb, Fb>,
                                                         CGAL::Exact_predicates_tag>;
  const auto outlines = text_outlines(label.text, label.height, style.stroke, kLandFactor * min_wall / 2);
  std::vector<Eigen::Vector2d> points;
  Cdt cdt;
  for (const auto& loop : outlines) {
    std::vector<Cdt::Vertex_handle> v;
    for (const Eigen::Vector2d& p : loop) {
      v.push_back(cdt.insert(Kernel::Point_2(p.x(), p.y())));
      v.back()->info() = static_cast<int>(points.size());
      points.push_back(p);
    }
    for (std::size_t k = 0; k < v.size(); ++k) cdt.insert_constraint(v[k], v[(k + 1) % v.size()]);
  }
  if (cdt.number_of_vertices() != points.size())
    throw std::runtime_error(fmt::format("the outlines of label '{}' touch or cross", label.text));
  // Faces inside: an odd number of outlines crossed from outside.
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::vector<std::pair<Cdt::Face_handle, int>> todo{{cdt.infinite_face(), 0}};
  while (!todo.empty()) {
    const auto [f, level] = todo.back();
    todo.pop_back();
    if (f->info() != -1) continue;
    f->info() = level;
    for (int i = 0; i < 3; ++i)
      if (f->neighbor(i)->info() == -1)
        todo.push_back({f->neighbor(i), level + (cdt.is_constrained(Cdt::Edge(f, i)) ? 1 : 0)});
  }
  const FaceFrame frame = frame_of(label.centre, label.normal, label.up);
  const int n = static_cast<int>(points.size());
  SurfaceMesh m;
  m.vertices.resize(2 * n, 3);
  for (int k = 0; k < n; ++k) {
    m.vertices.row(k) = frame.world({points[k].x(), points[k].y(), -label.depth});
    m.vertices.row(n + k) = frame.world({points[k].x(), points[k].y(), kAbove});
  }
  std::vector<Eigen::Vector3i> faces;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->info() % 2 == 1) {
      const int a = f->vertex(0)->info(), b = f->vertex(1)->info(), c = f->vertex(2)->info();
      faces.emplace_back(n + a, n + b, n + c); // the top, facing out of the face
      faces.emplace_back(a, c, b);             // the floor
    }
  int first = 0;
  for (const auto& loop : outlines) { // the walls: the inside lies left of each outline
    const int size = static_cast<int>(loop.size());
    for (int k = 0; k < size; ++k) {
      const int a = first + k, b = first + (k + 1) % size;
      faces.emplace_back(a, b, n + b);
      faces.emplace_back(a, n + b, n + a);
    }
    first += size;
  }
  m.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t k = 0; k < faces.size(); ++k) m.faces.row(static_cast<Eigen::Index>(k)) = faces[k];
  return m;
}

SurfaceMesh engrave(const SurfaceMesh& part, const std::vector<PlacedLabel>& labels, const LabelStyle& style,
                    double min_wall)
{
  if (labels.empty()) return part;
  SurfaceMesh cut;
  cut.vertices.resize(0, 3);
  cut.faces.resize(0, 3);
  for (const PlacedLabel& l : labels) { // disjoint solids: one mesh of several shells
    const SurfaceMesh s = label_solid(l, style, min_wall);
    const Eigen::Index nv = cut.num_vertices(), nf = cut.num_faces();
    cut.vertices.conservativeResize(nv + s.num_vertices(), 3);
    cut.vertices.bottomRows(s.num_vertices()) = s.vertices;
    cut.faces.conservativeResize(nf + s.num_faces(), 3);
    cut.faces.bottomRows(s.num_faces()) = s.faces.array() + static_cast<int>(nv);
  }
  return mesh_difference(part, cut);
}

} // namespace fibermold

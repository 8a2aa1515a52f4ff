#include "design/design_file.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "core/atomic_file.hpp"
#include "core/input_error.hpp"
#include "core/units.hpp"
#include "design/did_you_mean.hpp"
#include "design/unclosed_bracket.hpp"
#include "molds/silicone_presets.hpp"

namespace fibermold {

namespace fs = std::filesystem;

namespace {

/// A TOML number as a double. toml++ gives no double for an integer a double cannot hold exactly
/// (beyond 2^53, e.g. 9223372036854775807): that one is rounded, and the range checks judge it.
double as_double(const toml::node& n)
{
  if (const auto i = n.value_exact<std::int64_t>()) return static_cast<double>(*i);
  return n.value<double>().value_or(std::nan(""));
}

/// A unit in the design file and its factor to SI.
struct Unit {
  double to_si;
  const char* label;
};
constexpr Unit kMm{units::mm, " mm"};
constexpr Unit kKPa{units::kPa, " kPa"};
constexpr Unit kNone{1.0, ""};
constexpr Unit kPa{1.0, " Pa"};
constexpr Unit kDegree{units::degree, "°"};

/// An interval of admissible values, in design-file units.
struct Range {
  double lo = -HUGE_VAL, hi = HUGE_VAL;
  bool lo_open = false, hi_open = false;

  bool contains(double v) const { return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi); }
  std::string describe(const Unit& unit) const
  {
    const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
    if (has_lo && has_hi)
      return fmt::format("in {}{}, {}{}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]", unit.label);
    if (has_lo) return fmt::format("{} {}{}", lo_open ? ">" : "≥", lo, unit.label);
    return fmt::format("{} {}{}", hi_open ? "<" : "≤", hi, unit.label);
  }
};
Range closed(double lo, double hi) { return {lo, hi, false, false}; }
/// (0, hi]: a size, a rate or a tolerance, with the largest value that still means something.
Range above_zero(double hi) { return {0, hi, true, false}; }

/// The physical range of every number (docs/design-file.md, "Ranges"): wide enough for any soft
/// robot, mold and printer, narrow enough that the products the pipeline forms (a modulus times a
/// volume, a pressure times an area, a voxel count) stay far from overflow and underflow.
/// Coordinates and lengths in mm: 10 m.
constexpr double kMaxCoordinate = 1e4;
/// Strings (names, paths): a path of 4096 bytes is what Linux takes.
constexpr std::size_t kMaxString = 4096;
/// Names become file names with suffixes; a file name has at most 255 bytes.
constexpr std::size_t kMaxName = 100;

std::string format_number(double v) { return fmt::format("{}", v); }

/// A value written back in a message: quoted, and cut after 60 characters (a bad value can be megabytes).
std::string excerpt(std::string_view text, char quote = '"')
{
  if (text.size() <= 60) return fmt::format("{}{}{}", quote, text, quote);
  std::size_t cut = 57;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut; // not inside a UTF-8 character
  return fmt::format("{}{}…{} ({} characters)", quote, text.substr(0, cut), quote, text.size());
}
std::string format_vec3(const Vec3& v)
{
  return fmt::format("[{}, {}, {}]", format_number(v.x()), format_number(v.y()), format_number(v.z()));
}
std::string format_points(const std::vector<Vec3>& points, double from_si)
{
  std::vector<std::string> parts;
  for (const Vec3& p : points) parts.push_back(format_vec3(p / from_si));
  return fmt::format("[{}]", fmt::join(parts, ", "));
}

/// What all sections share: the file, its folder, the problems found, the effective values.
struct Context {
  fs::path file;
  fs::path folder;
  std::vector<Diagnostic> problems;
  std::map<std::string, std::string> values;
  std::map<std::string, toml::source_region> sources; ///< where each key given was written (the last of equal names)

  toml::source_region source_of(const std::string& key) const
  {
    auto it = sources.find(key);
    return it == sources.end() ? toml::source_region{} : it->second;
  }

  void error(const toml::source_region& where, std::string key, std::string message)
  {
    problems.push_back({file, static_cast<int>(where.begin.line), static_cast<int>(where.begin.column), std::move(key),
                        std::move(message)});
  }
};

/// One table of the design file. Reads keys with defaults and checks, records each key's effective
/// value, and on finish() reports every key that nobody asked for, with the closest valid key.
class Section {
public:
  Section(Context& ctx, const toml::table* table, std::string display, toml::source_region where)
      : ctx_(ctx), table_(table), display_(std::move(display)), where_(where)
  {
  }

  const std::string& display() const { return display_; }
  const toml::source_region& where() const { return where_; }
  Context& context() { return ctx_; }

  /// The raw node of `key`, or null. Marks the key as known.
  const toml::node* node(std::string_view key)
  {
    known_.emplace_back(key);
    const toml::node* n = table_ ? table_->get(key) : nullptr;
    if (n) ctx_.sources[key_name(key)] = n->source();
    return n;
  }

  toml::source_region where_of(const toml::node* n) const { return n ? n->source() : where_; }
  std::string key_name(std::string_view key) const { return display_ + "." + std::string(key); }

  void error(const toml::node* n, std::string_view key, std::string message)
  {
    ctx_.error(where_of(n), key_name(key), std::move(message));
  }
  void record(std::string_view key, std::string value) { ctx_.values[key_name(key)] = std::move(value); }

  void missing(std::string_view key, std::string_view what)
  {
    ctx_.error(where_, key_name(key), fmt::format("missing; required ({})", what));
  }

  std::optional<double> read_number(const toml::node* n, std::string_view key, const Range& range, const Unit& unit)
  {
    if (!n->is_number()) {
      error(n, key, fmt::format("expected a number, got {}", type_name(*n)));
      return std::nullopt;
    }
    const double v = as_double(*n);
    if (!std::isfinite(v) || !range.contains(v)) {
      error(n, key, fmt::format("must be {}, got {}", range.describe(unit), format_number(v)));
      return std::nullopt;
    }
    return v;
  }

  /// A number in design units, returned in SI.
  double number(std::string_view key, double fallback, const Range& range, const Unit& unit = kNone)
  {
    double v = fallback;
    if (const toml::node* n = node(key))
      if (auto read = read_number(n, key, range, unit)) v = *read;
    record(key, format_number(v));
    return v * unit.to_si;
  }

  std::optional<double> optional_number(std::string_view key, const Range& range, const Unit& unit = kNone)
  {
    const toml::node* n = node(key);
    std::optional<double> v = n ? read_number(n, key, range, unit) : std::nullopt;
    record(key, v ? format_number(*v) : "auto");
    if (v) return *v * unit.to_si;
    return std::nullopt;
  }

  int integer(std::string_view key, int fallback, int lo, int hi)
  {
    int v = fallback;
    if (const toml::node* n = node(key)) {
      if (!n->is_integer()) {
        error(n, key, fmt::format("expected an integer, got {}", type_name(*n)));
      } else {
        const auto read = *n->value<std::int64_t>();
        if (read < lo || read > hi)
          error(n, key, fmt::format("must be in [{}, {}], got {}", lo, hi, read));
        else
          v = static_cast<int>(read);
      }
    }
    record(key, std::to_string(v));
    return v;
  }

  bool boolean(std::string_view key, bool fallback)
  {
    bool v = fallback;
    if (const toml::node* n = node(key)) {
      if (!n->is_boolean())
        error(n, key, fmt::format("expected true or false, got {}", type_name(*n)));
      else
        v = *n->value<bool>();
    }
    record(key, v ? "true" : "false");
    return v;
  }

  std::optional<std::string> read_string(const toml::node* n, std::string_view key)
  {
    if (!n->is_string()) {
      error(n, key, fmt::format("expected a string, got {}", type_name(*n)));
      return std::nullopt;
    }
    std::string text = *n->value<std::string>();
    if (text.find('\0') != std::string::npos) {
      error(n, key, fmt::format("{} contains a NUL character (\\u0000)", excerpt(text.substr(0, text.find('\0')))));
      return std::nullopt;
    }
    if (text.size() > kMaxString) {
      error(n, key, fmt::format("{} is longer than {} characters", excerpt(text), kMaxString));
      return std::nullopt;
    }
    return text;
  }

  /// A string; required when `fallback` is empty.
  std::string string(std::string_view key, std::optional<std::string> fallback, std::string_view what = "")
  {
    std::optional<std::string> v = fallback;
    if (const toml::node* n = node(key)) {
      if (auto read = read_string(n, key)) {
        if (read->empty())
          error(n, key, "must not be empty");
        else
          v = std::move(read);
      }
    } else if (!fallback) {
      missing(key, what);
    }
    record(key, fmt::format("\"{}\"", v.value_or("")));
    return v.value_or("");
  }

  std::string choice(std::string_view key, std::string fallback, const std::vector<std::string>& allowed)
  {
    std::string v = fallback;
    if (const toml::node* n = node(key)) {
      if (auto read = read_string(n, key)) {
        if (std::find(allowed.begin(), allowed.end(), *read) != allowed.end()) {
          v = *read;
        } else {
          std::string message =
              fmt::format("unknown value {}; expected one of: {}", excerpt(*read), fmt::join(allowed, ", "));
          if (auto hint = closest_match(*read, allowed)) message += fmt::format(" (did you mean \"{}\"?)", *hint);
          error(n, key, message);
        }
      }
    }
    record(key, fmt::format("\"{}\"", v));
    return v;
  }

  /// A choice of an enum's named values (core/names.hpp).
  template <typename E, std::size_t N>
  E choice_of(std::string_view key, E fallback, const std::array<Named<E>, N>& names)
  {
    return *value_in(names, choice(key, std::string(name_in(names, fallback)), names_of(names)));
  }

  /// Three numbers, each within ±`bound` (design units).
  std::optional<Vec3> read_vec3(const toml::node* n, std::string_view key, const Unit& unit, double bound)
  {
    const toml::array* a = n->as_array();
    if (!a || a->size() != 3 || !std::all_of(a->begin(), a->end(), [](const toml::node& e) { return e.is_number(); })) {
      error(n, key,
            fmt::format("expected three numbers [x, y, z]{}", unit.label[0] ? fmt::format(" in{}", unit.label) : ""));
      return std::nullopt;
    }
    Vec3 v(as_double((*a)[0]), as_double((*a)[1]), as_double((*a)[2]));
    if (!v.allFinite() || v.cwiseAbs().maxCoeff() > bound) {
      error(n, key,
            fmt::format("every coordinate must be in [{}, {}]{}, got {}", -bound, bound, unit.label, format_vec3(v)));
      return std::nullopt;
    }
    return v;
  }

  /// Three numbers in design units, returned in SI. `unit_length`: normalised, must be non-zero.
  Vec3 vec3(std::string_view key, const Vec3& fallback, const Unit& unit, double bound, bool unit_length = false)
  {
    Vec3 v = fallback;
    if (const toml::node* n = node(key)) {
      if (auto read = read_vec3(n, key, unit, bound)) {
        if (unit_length && read->norm() == 0)
          error(n, key, "must not be the zero vector");
        else
          v = *read;
      }
    }
    if (unit_length && v.norm() > 0) v.normalize();
    record(key, format_vec3(v));
    if (unit_length) return v;
    return v * unit.to_si;
  }

  std::optional<Vec3> optional_vec3(std::string_view key, const Unit& unit, double bound)
  {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    auto v = read_vec3(n, key, unit, bound);
    if (v) record(key, format_vec3(*v));
    if (v) return *v * unit.to_si;
    return std::nullopt;
  }

  /// A list of at least `min_count` points [[x, y, z], ...] in design units, returned in SI.
  std::vector<Vec3> points(std::string_view key, const Unit& unit, std::size_t min_count, bool required)
  {
    std::vector<Vec3> points;
    const toml::node* n = node(key);
    if (!n) {
      if (required) missing(key, fmt::format("a list of at least {} points [x, y, z]", min_count));
      return points;
    }
    const toml::array* a = n->as_array();
    if (!a) {
      error(n, key, fmt::format("expected a list of points [[x, y, z], ...], got {}", type_name(*n)));
      return points;
    }
    bool ok = true;
    for (const toml::node& element : *a) {
      const std::string entry = fmt::format("{}[{}]", key, points.size() + 1);
      ctx_.sources[key_name(entry)] = element.source(); // a later problem with one point names its place
      auto p = read_vec3(&element, entry, unit, kMaxCoordinate);
      ok = ok && p.has_value();
      points.push_back(p.value_or(Vec3::Zero()));
    }
    if (ok && points.size() < min_count)
      error(n, key, fmt::format("needs at least {} points, got {}", min_count, points.size()));
    record(key, format_points(points, 1.0));
    for (Vec3& p : points) p *= unit.to_si;
    return ok ? points : std::vector<Vec3>{};
  }

  /// A file path, resolved against the design file's folder; must exist.
  fs::path file(std::string_view key, bool required, std::string_view what)
  {
    const toml::node* n = node(key);
    if (!n) {
      if (required) missing(key, what);
      return {};
    }
    auto name = read_string(n, key);
    if (!name) return {};
    fs::path path = fs::path(*name).is_absolute() ? fs::path(*name) : ctx_.folder / *name;
    path = path.lexically_normal();
    record(key, fmt::format("\"{}\"", path.lexically_proximate(ctx_.folder).string()));
    std::error_code ec;
    if (!fs::exists(path, ec)) {
      error(n, key, fmt::format("file not found: {}", path.string()));
      return {};
    }
    if (!fs::is_regular_file(path, ec)) {
      error(n, key, fmt::format("not a regular file: {}", path.string()));
      return {};
    }
    return path;
  }

  /// A sub-table (inline `{...}` or `[a.b]`), or null after reporting a type error.
  const toml::table* table(std::string_view key)
  {
    const toml::node* n = node(key);
    if (!n) return nullptr;
    if (!n->is_table()) {
      error(n, key, fmt::format("expected a table {{ ... }}, got {}", type_name(*n)));
      return nullptr;
    }
    return n->as_table();
  }

  /// Reports every key of this table that was never asked for.
  void finish()
  {
    if (!table_) return;
    for (auto&& [key, value] : *table_) {
      const std::string name(key.str());
      if (std::find(known_.begin(), known_.end(), name) != known_.end()) continue;
      std::string message = fmt::format("unknown key {} in {}", excerpt(name, '\''), display_);
      if (auto hint = closest_match(name, known_))
        message += fmt::format("; did you mean '{}'?", *hint);
      else
        message += fmt::format("; valid keys: {}", fmt::join(known_, ", "));
      ctx_.error(key.source(), display_ + "." + name, message);
    }
  }

  static std::string type_name(const toml::node& n)
  {
    switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date or time";
    }
  }

private:
  Context& ctx_;
  const toml::table* table_;
  std::string display_;
  toml::source_region where_;
  std::vector<std::string> known_;
};

const std::vector<std::string> kSections = {"design",  "material", "mesh",           "sim",    "fixed",
                                            "muscle",  "fiber",    "tracking_curve", "target", "optimize",
                                            "collide", "mold",     "export"};
const std::vector<std::string> kArraySections = {"fixed", "fiber", "tracking_curve", "target"};

} // namespace

const std::vector<std::string>& design_sections() { return kSections; }

bool is_array_section(std::string_view section)
{
  return std::find(kArraySections.begin(), kArraySections.end(), section) != kArraySections.end();
}

std::string default_design_name(const fs::path& file)
{
  const std::string stem = file.stem().string();
  if (stem == "design" && file.parent_path().has_filename()) return file.parent_path().filename().string();
  return stem;
}

namespace {

/// Names become folder and file names (out/<design>/, targets/<name>.vtu): letters, digits, '-', '_'
/// and '.', not starting with '.'.
void check_name(Section& s, const std::string& name)
{
  const bool ok = !name.empty() && name[0] != '.' && std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '-' || c == '_' || c == '.';
  });
  if (!ok && !name.empty())
    s.error(s.node("name"), "name",
            fmt::format("{} cannot name a file: use letters, digits, '-', '_' and '.', not "
                        "starting with '.'",
                        excerpt(name)));
  else if (name.size() > kMaxName)
    s.error(s.node("name"), "name",
            fmt::format("{} is longer than {} characters: it names files and folders", excerpt(name), kMaxName));
}

DesignOptions read_design(Section s, const fs::path& file)
{
  DesignOptions o;
  o.name = s.string("name", default_design_name(file));
  check_name(s, o.name);
  o.surface = s.file("surface", true, "the body's closed surface mesh, e.g. surface = \"body.stl\"");
  o.units = s.choice("units", "mm", {"mm", "cm", "m", "in"});
  o.surface_scale = o.units == "mm" ? 1e-3 : o.units == "cm" ? 1e-2 : o.units == "m" ? 1.0 : 0.0254;
  s.finish();
  return o;
}

MaterialOptions read_material(Section s)
{
  MaterialOptions o;
  o.model = s.choice("model", o.model, {"neo-hookean"});
  std::vector<std::string> presets;
  for (const SiliconePreset& p : silicone_presets()) presets.push_back(p.key);
  o.preset = s.choice("preset", o.preset, presets);
  // A preset's figures are the defaults; the keys written beside it override them.
  if (const SiliconePreset* p = find_silicone_preset(o.preset)) {
    o.youngs_modulus = p->youngs_modulus();
    o.poisson_ratio = kPresetPoissonRatio;
    o.density = p->density;
  }
  o.youngs_modulus = s.number("youngs_modulus", o.youngs_modulus, closed(100, 1e10), kPa);
  o.poisson_ratio = s.number("poisson_ratio", o.poisson_ratio, {0.0, 0.5, false, true});
  o.density = s.number("density", o.density, closed(0, 3e4), {1.0, " kg/m³"});
  o.gravity = s.vec3("gravity", o.gravity, {1.0, " m/s²"}, 1e3);
  s.finish();
  return o;
}

MeshOptions read_mesh(Section s)
{
  MeshOptions o;
  o.edge_length = s.optional_number("edge_length", closed(0.01, kMaxCoordinate), kMm);
  o.radius_edge_ratio = s.number("radius_edge_ratio", o.radius_edge_ratio, closed(1.1, 10.0));
  o.min_dihedral_deg = s.number("min_dihedral_deg", o.min_dihedral_deg, closed(0, 18), {1.0, "°"});
  o.max_tets = s.integer("max_tets", o.max_tets, 1000, 100'000'000);
  o.repair = s.boolean("repair", o.repair);
  if (const toml::node* n = s.node("remesh"))
    s.error(n, "remesh",
            "replaced by surface_triangles = \"remesh\" (and \"auto\", the default, remeshes a surface much denser "
            "than edge_length by itself)");
  o.surface_triangles = s.choice_of("surface_triangles", o.surface_triangles, kSurfaceTrianglesNames);
  s.finish();
  return o;
}

SimOptions read_sim(Section s)
{
  SimOptions o;
  o.basis = s.choice_of("basis", o.basis, kBasisNames);
  o.mls_radius = s.number("mls_radius", o.mls_radius, {1.0, 10.0, true, false});
  const toml::node* q = s.node("quadrature_points");
  o.quadrature_points = s.integer("quadrature_points", o.quadrature_points, 1, 8);
  if (o.quadrature_points != 1 && o.quadrature_points != 4 && o.quadrature_points != 8) {
    s.error(q, "quadrature_points", fmt::format("must be 1, 4 or 8, got {}", o.quadrature_points));
  }
  s.finish();
  return o;
}

/// A region: exactly one of box = { min, max }, vertices = [...], or (for loads) point = [...].
Region read_region(Section& s, bool allow_point)
{
  Region r;
  int given = 0;
  if (const toml::table* box = s.table("box")) {
    ++given;
    Section b(s.context(), box, s.display() + ".box", box->source());
    const toml::node* min_node = b.node("min");
    Vec3 lo = b.vec3("min", Vec3::Zero(), kMm, kMaxCoordinate);
    Vec3 hi = b.vec3("max", Vec3::Zero(), kMm, kMaxCoordinate);
    if (!box->get("min")) b.missing("min", "the box's lower corner [x, y, z] in mm");
    if (!box->get("max")) b.missing("max", "the box's upper corner [x, y, z] in mm");
    if (box->get("min") && box->get("max") && !(lo.array() < hi.array()).all())
      b.error(min_node, "min", "must be below max in every coordinate");
    b.finish();
    r.box = std::array<Vec3, 2>{lo, hi};
  }
  if (const toml::node* n = s.node("vertices")) {
    ++given;
    const toml::array* a = n->as_array();
    if (!a || a->empty() || !std::all_of(a->begin(), a->end(), [](const toml::node& e) {
          return e.is_integer() && *e.value<std::int64_t>() >= 0 && *e.value<std::int64_t>() < (1ll << 31);
        })) {
      s.error(n, "vertices", "expected a non-empty list of surface vertex indices (integers ≥ 0)");
    } else {
      for (const toml::node& e : *a) r.vertices.push_back(static_cast<int>(*e.value<std::int64_t>()));
      s.record("vertices", fmt::format("[{}]", fmt::join(r.vertices, ", ")));
    }
  }
  if (allow_point) {
    if (auto p = s.optional_vec3("point", kMm, kMaxCoordinate)) {
      ++given;
      r.point = p;
    }
  }
  if (given != 1) {
    s.context().error(s.where(), s.display(),
                      fmt::format("give exactly one of box = {{ min, max }}, vertices = [...]{}; got {}",
                                  allow_point ? ", point = [x, y, z]" : "", given));
  }
  return r;
}

/// Reads an array of tables ([[name]]) into one Section per entry, named by its `name` key or its
/// 1-based index. Reports a plain table where an array of tables is expected.
template <typename Read> void for_each_entry(Context& ctx, const toml::table& root, const std::string& name, Read read)
{
  const toml::node* n = root.get(name);
  if (!n) return;
  const toml::array* a = n->as_array();
  if (!a || !a->is_array_of_tables()) {
    ctx.error(n->source(), "[" + name + "]", fmt::format("must be an array of tables: write [[{}]]", name));
    return;
  }
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::table& t = *(*a)[i].as_table();
    // Unnamed: the default name the entry takes (entry_name), so that a stage naming it later finds its line.
    std::string id = name == "tracking_curve" ? fmt::format("curve{}", i + 1)
                     : name == "fixed"        ? fmt::format("fixed{}", i + 1)
                                              : std::to_string(i + 1);
    if (const toml::node* nn = t.get("name");
        nn && nn->is_string() && !nn->value<std::string>()->empty() && nn->value<std::string>()->size() <= kMaxName)
      id = *nn->value<std::string>(); // a longer name is refused, and labelled by its index meanwhile
    read(Section(ctx, &t, fmt::format("[{}.{}]", name, id), t.source()), i + 1);
  }
}

std::string entry_name(Section& s, std::string_view kind, std::size_t index, bool required)
{
  const std::string fallback = fmt::format("{}{}", kind, index);
  std::string name = required ? s.string("name", std::nullopt, "a unique name") : s.string("name", fallback);
  check_name(s, name);
  return name;
}

MuscleOptions read_muscle(Section s)
{
  MuscleOptions o;
  o.model.diameter = s.number("diameter", o.model.diameter / units::mm, closed(0.1, 100), kMm);
  o.max_pressure = s.number("max_pressure", o.max_pressure / units::kPa, closed(0.1, 1e4), kKPa);
  o.min_bend_radius =
      s.number("min_bend_radius", kBendRadiusPerDiameter * o.model.diameter / units::mm, closed(0, 1e4), kMm);
  o.segments_per_length = s.number("segments_per_mm", o.segments_per_length * units::mm, closed(0.01, 10)) / units::mm;
  auto line = [&](std::string_view key, TwoPieceLine fallback) {
    std::array<double, 4> c{fallback.slope_low, fallback.intercept_low, fallback.slope_high, fallback.intercept_high};
    if (const toml::node* n = s.node(key)) {
      const toml::array* a = n->as_array();
      const auto pair = [](const toml::node& e) {
        const toml::array* p = e.as_array();
        return p && p->size() == 2 && (*p)[0].is_number() && (*p)[1].is_number();
      };
      if (!a || a->size() != 2 || !std::all_of(a->begin(), a->end(), pair)) {
        s.error(n, key, "expected two lines [[slope_low, intercept_low Pa], [slope_high, intercept_high Pa]]");
      } else {
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j) c[2 * i + j] = as_double((*(*a)[i].as_array())[j]);
        // Moduli-like figures: the default taut line's intercept is 4.07e9 Pa.
        if (!std::all_of(c.begin(), c.end(), [](double v) { return std::isfinite(v) && std::abs(v) <= 1e12; }))
          s.error(n, key, "every coefficient must be in [-1e12, 1e12]");
      }
    }
    s.record(key, fmt::format("[[{}, {}], [{}, {}]]", c[0], c[1], c[2], c[3]));
    return TwoPieceLine{c[0], c[1], c[2], c[3]};
  };
  o.model.stiffness = line("stiffness", o.model.stiffness);
  o.model.taut = line("taut", o.model.taut);
  o.model.rest_strain_slope =
      s.number("rest_strain_slope", o.model.rest_strain_slope, closed(-1e-3, 1e-3), {1.0, " 1/Pa"});
  o.model.rest_strain_intercept = s.number("rest_strain_intercept", o.model.rest_strain_intercept, closed(-0.9, 0.9));
  o.model.smoothing = s.number("smoothing", o.model.smoothing / units::kPa, above_zero(1e4), kKPa);
  for (const auto& [key, line] : {std::pair{"stiffness", o.model.stiffness}, std::pair{"taut", o.model.taut}})
    if (line.slope_low == line.slope_high && line.intercept_low != line.intercept_high)
      s.error(s.node(key), key, "the two lines are parallel and distinct: they never meet");
  // The muscle must keep a positive length up to the highest pressure: 1 + ε_L(p) > 0.05.
  for (const double p : {0.0, o.max_pressure})
    if (!(1 + o.model.rest_strain_slope * p + o.model.rest_strain_intercept > 0.05))
      s.error(s.node(p == 0 ? "rest_strain_intercept" : "max_pressure"),
              p == 0 ? "rest_strain_intercept" : "max_pressure",
              fmt::format("at {} kPa the muscle would contract by more than 95 % (ε_L = {:.3g}): outside any model",
                          p / units::kPa, o.model.rest_strain_slope * p + o.model.rest_strain_intercept));
  s.finish();
  return o;
}

std::vector<FixedRegion> read_fixed(Context& ctx, const toml::table& root)
{
  std::vector<FixedRegion> fixed;
  for_each_entry(ctx, root, "fixed", [&](Section s, std::size_t i) {
    FixedRegion f;
    f.name = entry_name(s, "fixed", i, false);
    f.region = read_region(s, false);
    s.finish();
    fixed.push_back(std::move(f));
  });
  return fixed;
}

std::vector<Fiber> read_fibers(Context& ctx, const toml::table& root)
{
  std::vector<Fiber> fibers;
  for_each_entry(ctx, root, "fiber", [&](Section s, std::size_t i) {
    Fiber f;
    f.name = entry_name(s, "fiber", i, true);
    f.points = s.points("points", kMm, 2, true);
    f.tangents = s.points("tangents", kMm, 0, false);
    if (!f.tangents.empty() && f.tangents.size() != f.points.size())
      s.error(s.node("tangents"), "tangents",
              fmt::format("needs one tangent per point: {} points, {} tangents", f.points.size(), f.tangents.size()));
    s.finish();
    fibers.push_back(std::move(f));
  });
  return fibers;
}

std::vector<TrackingCurve> read_tracking_curves(Context& ctx, const toml::table& root)
{
  std::vector<TrackingCurve> curves;
  for_each_entry(ctx, root, "tracking_curve", [&](Section s, std::size_t i) {
    TrackingCurve c;
    c.name = entry_name(s, "curve", i, false);
    c.points = s.points("points", kMm, 2, true);
    c.samples = s.integer("samples", c.samples, 2, 100000);
    c.weight_position = s.number("weight_position", c.weight_position, closed(0, 1e9));
    c.weight_orientation = s.number("weight_orientation", c.weight_orientation, closed(0, 1e9));
    s.finish();
    curves.push_back(std::move(c));
  });
  return curves;
}

Load read_load(Section s)
{
  Load l;
  l.region = read_region(s, true);
  l.force = s.optional_vec3("force", {1.0, " N"}, 1e5);
  l.torque = s.optional_vec3("torque", {1.0, " N·m"}, 1e4);
  if (!l.force && !l.torque)
    s.context().error(s.where(), s.display(), "give force = [x, y, z] (N) and/or torque = [x, y, z] (N·m)");
  if (l.region.point && l.torque)
    s.context().error(s.where(), s.display(), "a point load takes a force, not a torque; use a box region");
  s.finish();
  return l;
}

/// An angle_deg given as a number other than 0 that reads as 0: out of its range, and said so.
bool refused_angle(const toml::node* angle) { return angle && angle->value<double>().value_or(0) != 0; }

Pose read_pose(Section s)
{
  Pose p;
  p.region = read_region(s, false);
  p.axis = s.vec3("axis", p.axis, kNone, kMaxCoordinate, true);
  p.angle = s.number("angle_deg", 0.0, closed(-180, 180), kDegree);
  p.about = s.optional_vec3("about", kMm, kMaxCoordinate);
  p.translation = s.vec3("translation", p.translation, kMm, kMaxCoordinate);
  p.curl_from = s.optional_vec3("curl_from", kMm, kMaxCoordinate);
  if (p.curl_from && (s.node("translation") || s.node("about")))
    s.context().error(s.where(), s.display(),
                      "curl_from places the region where a uniform curl takes it: leave out translation and about");
  else if (p.curl_from && p.angle == 0 && !refused_angle(s.node("angle_deg"))) // a refused one is said where it is
    s.context().error(s.where(), s.display(), "curl_from needs the curl's angle: give angle_deg (and axis)");
  else if (!s.node("angle_deg") && !s.node("translation"))
    s.context().error(s.where(), s.display(), "give angle_deg (with axis, about) and/or translation = [x, y, z] (mm)");
  s.finish();
  return p;
}

Target read_target(Section s, std::size_t index, const MuscleOptions& muscle, const std::vector<Fiber>& fibers)
{
  Target t;
  t.name = entry_name(s, "target", index, true);
  const std::string kind_name = s.choice("kind", "", names_of(kTargetKindNames));
  if (kind_name.empty() && !s.node("kind")) s.missing("kind", "forces | surface | fibers | pose");
  const std::optional<TargetKind> kind = value_in(kTargetKindNames, kind_name);
  if (kind) t.kind = *kind;

  if (const toml::node* n = s.node("load")) {
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables() || a->empty()) {
      s.error(n, "load", "expected a list of loads [{ box = {...}, force = [...] }, ...]");
    } else {
      for (std::size_t i = 0; i < a->size(); ++i) {
        const toml::table& lt = *(*a)[i].as_table();
        t.loads.push_back(
            read_load(Section(s.context(), &lt, fmt::format("{}.load[{}]", s.display(), i + 1), lt.source())));
      }
    }
  }
  if (const toml::node* n = s.node("pose")) {
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables() || a->empty()) {
      s.error(n, "pose",
              "expected a list of poses [{ box = {...}, axis = [0, 0, 1], angle_deg = 60, about = [...] }, ...]");
    } else {
      for (std::size_t i = 0; i < a->size(); ++i) {
        const toml::table& pt = *(*a)[i].as_table();
        t.poses.push_back(
            read_pose(Section(s.context(), &pt, fmt::format("{}.pose[{}]", s.display(), i + 1), pt.source())));
      }
    }
  }
  t.surface = s.file("surface", false, "");
  t.strain_penalty = s.number("strain_penalty", 0.0, closed(0, 1e9));
  t.weight = s.number("weight", t.weight, above_zero(1e9));

  if (const toml::node* n = s.node("fibers")) {
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables() || a->empty()) {
      s.error(n, "fibers", "expected a list of actuations [{ name = \"m1\", pressure = 300 }, ...]");
    } else {
      for (std::size_t i = 0; i < a->size(); ++i) {
        const toml::table& ft = *(*a)[i].as_table();
        Section f(s.context(), &ft, fmt::format("{}.fibers[{}]", s.display(), i + 1), ft.source());
        FiberActuation act;
        act.name = f.string("name", std::nullopt, "the fiber's name");
        act.pressure = f.number("pressure", 0.0, closed(0, muscle.max_pressure / units::kPa), kKPa);
        if (!ft.get("pressure")) f.missing("pressure", "in kPa");
        act.points = f.points("points", kMm, 2, false);
        const bool known =
            std::any_of(fibers.begin(), fibers.end(), [&](const Fiber& fb) { return fb.name == act.name; });
        if (act.points.empty() && !known && !act.name.empty())
          f.error(ft.get("name"), "name", fmt::format("no [[fiber]] named {} and no points given", excerpt(act.name)));
        f.finish();
        t.fibers.push_back(std::move(act));
      }
    }
  }

  if (const toml::node* n = s.node("actuators")) {
    const toml::array* a = n->as_array();
    if (!a || a->empty())
      s.error(n, "actuators", "expected a non-empty list of [[fiber]] names, e.g. [\"m1\", \"m2\"]");
    else
      for (const toml::node& e : *a) {
        const auto name = e.value<std::string>();
        if (!name || std::none_of(fibers.begin(), fibers.end(), [&](const Fiber& f) { return f.name == *name; }))
          s.error(&e, "actuators", "expected the name of a [[fiber]]");
        else if (std::find(t.actuators.begin(), t.actuators.end(), *name) == t.actuators.end())
          t.actuators.push_back(*name);
      }
    std::vector<std::string> quoted;
    for (const std::string& f : t.actuators) quoted.push_back("\"" + f + "\"");
    s.record("actuators", fmt::format("[{}]", fmt::join(quoted, ", ")));
  }

  const auto forbid = [&](bool present, std::string_view key) {
    if (present) s.error(s.node(key), key, fmt::format("not used by kind = \"{}\"", kind_name));
  };
  if (kind == TargetKind::forces) {
    if (t.loads.empty() && !s.node("load")) s.missing("load", "the loads that make this target");
  } else if (kind == TargetKind::surface) {
    if (!s.node("surface")) s.missing("surface", "the deformed copy of the body's surface");
  } else if (kind == TargetKind::fibers) {
    if (!s.node("fibers")) s.missing("fibers", "the fibers and pressures that make this target");
  } else if (kind == TargetKind::pose) {
    if (!s.node("pose")) s.missing("pose", "the regions and the rigid motions they are moved by");
  }
  if (kind) {
    forbid(kind != TargetKind::forces && !t.loads.empty(), "load");
    forbid(kind != TargetKind::surface && !t.surface.empty(), "surface");
    forbid(kind != TargetKind::fibers && !t.fibers.empty(), "fibers");
    forbid(kind != TargetKind::pose && !t.poses.empty(), "pose");
  }
  s.finish();
  return t;
}

OptimizeOptions read_optimize(Section s)
{
  OptimizeOptions o;
  o.enabled = s.boolean("enabled", o.enabled);
  o.strategy = s.choice_of("strategy", o.strategy, kStrategyNames);
  o.method = s.choice_of("method", o.method, kMethodNames);
  o.max_iterations = s.integer("max_iterations", o.max_iterations, 0, 1000000);
  o.route_only_iterations = s.integer("route_only_iterations", o.route_only_iterations, 0, 1000000);
  o.starts = s.integer("starts", o.starts, 1, 100);
  o.gradient_tolerance = s.number("gradient_tolerance", o.gradient_tolerance, above_zero(1));
  o.relative_tolerance = s.number("relative_tolerance", o.relative_tolerance, above_zero(1));
  o.decrease_tolerance = s.number("decrease_tolerance", o.decrease_tolerance, above_zero(1));
  o.weight_curvature = s.number("weight_curvature", o.weight_curvature, closed(0, 1e9));
  o.weight_skin_barrier = s.number("weight_skin_barrier", o.weight_skin_barrier, closed(0, 1e9));
  o.weight_bend_barrier = s.number("weight_bend_barrier", o.weight_bend_barrier, closed(0, 1e9));
  o.weight_pressure_barrier = s.number("weight_pressure_barrier", o.weight_pressure_barrier, closed(0, 1e9));
  o.refine = s.boolean("refine", o.refine);
  s.finish();
  return o;
}

CollideOptions read_collide(Section s)
{
  CollideOptions o;
  o.clearance = s.number("clearance", o.clearance / units::mm, closed(0, 100), kMm);
  o.smoothness = s.number("smoothness", o.smoothness / units::mm, above_zero(kMaxCoordinate), kMm);
  o.samples_per_length = s.number("samples_per_mm", o.samples_per_length * units::mm, above_zero(100)) / units::mm;
  o.reoptimize = s.boolean("reoptimize", o.reoptimize);
  s.finish();
  return o;
}

MoldOptions read_mold(Section s)
{
  MoldOptions o;
  const auto mm = [&](std::string_view key, double si, Range r) { return s.number(key, si / units::mm, r, kMm); };
  o.block.wall = mm("wall", o.block.wall, above_zero(1000));
  o.voxel = mm("voxel", o.voxel, closed(0.01, 5.0));
  o.pull = s.vec3("pull", o.pull, kNone, kMaxCoordinate, true);
  if (const toml::node* n = s.node("parting")) {
    if (n->is_string()) {
      if (*n->value<std::string>() != "auto")
        s.error(n, "parting", "expected \"auto\" or { point = [x, y, z], normal = [x, y, z] }");
      s.record("parting", "\"auto\"");
    } else if (const toml::table* t = n->as_table()) {
      Section p(s.context(), t, s.display() + ".parting", t->source());
      if (!t->get("point")) p.missing("point", "a point on the parting plane, mm");
      if (!t->get("normal")) p.missing("normal", "the parting plane's normal");
      PartingPlane plane{p.vec3("point", Vec3::Zero(), kMm, kMaxCoordinate),
                         p.vec3("normal", Vec3::UnitZ(), kNone, kMaxCoordinate, true)};
      p.finish();
      o.parting = plane;
    } else {
      s.error(n, "parting", "expected \"auto\" or { point = [x, y, z], normal = [x, y, z] }");
    }
  } else {
    s.record("parting", "\"auto\"");
  }
  o.block.keys = s.integer("keys", o.block.keys, 0, 8);
  o.block.key_shape = s.choice_of("key_shape", o.block.key_shape, kKeyShapeNames);
  o.block.key_diameter = mm("key_diameter", o.block.key_diameter, above_zero(100));
  o.block.key_clearance = mm("key_clearance", o.block.key_clearance, closed(0, 10));
  o.block.sprue_diameter = mm("sprue_diameter", o.block.sprue_diameter, above_zero(100));
  o.block.vents = s.integer("vents", o.block.vents, 0, 16);
  o.block.vent_diameter = mm("vent_diameter", o.block.vent_diameter, above_zero(100));
  o.groove_clearance = mm("groove_clearance", o.groove_clearance, closed(0, 10));
  o.min_silicone = mm("min_silicone", o.min_silicone, closed(0, 100));
  o.end_channel_length = mm("end_channel_length", o.end_channel_length, closed(0, 1000));
  o.end_channel_diameter = mm("end_channel_diameter", o.end_channel_diameter, above_zero(100));
  o.block.screw_holes = s.integer("screw_holes", o.block.screw_holes, 0, 16);
  o.block.screw_diameter = mm("screw_diameter", o.block.screw_diameter, above_zero(100));
  o.draft_deg = s.number("draft_deg", o.draft_deg, {0.0, 15.0, false, false}, {1.0, "°"});
  o.shrink = s.number("shrink", o.shrink, {0.0, 0.2, false, false});
  o.labels = s.boolean("labels", o.labels);
  s.finish();
  return o;
}

ExportOptions read_export(Section s)
{
  ExportOptions o;
  const std::vector<std::string> allowed{"stl", "3mf"};
  if (const toml::node* n = s.node("formats")) {
    const toml::array* a = n->as_array();
    std::vector<std::string> formats;
    bool ok = a && !a->empty();
    if (ok) {
      for (const toml::node& e : *a) {
        auto f = e.value<std::string>();
        if (!f || std::find(allowed.begin(), allowed.end(), *f) == allowed.end()) {
          s.error(&e, "formats", fmt::format("unknown format; expected some of: {}", fmt::join(allowed, ", ")));
          ok = false;
        } else if (std::find(formats.begin(), formats.end(), *f) == formats.end()) {
          formats.push_back(*f);
        }
      }
    } else {
      s.error(n, "formats", "expected a non-empty list, e.g. [\"stl\", \"3mf\"]");
    }
    if (ok) o.formats = formats;
  }
  std::vector<std::string> quoted;
  for (const std::string& f : o.formats) quoted.push_back("\"" + f + "\"");
  s.record("formats", fmt::format("[{}]", fmt::join(quoted, ", ")));
  o.printer_volume = s.vec3("printer_volume", o.printer_volume / units::mm, kMm, kMaxCoordinate);
  if (!(o.printer_volume.array() > 0).all())
    s.error(s.node("printer_volume"), "printer_volume", "every side must be > 0 mm");
  o.min_wall = s.number("min_wall", o.min_wall / units::mm, above_zero(100), kMm);
  s.finish();
  return o;
}

template <typename T> void check_unique_names(Context& ctx, const std::vector<T>& items, std::string_view section)
{
  std::set<std::string> seen;
  for (const T& item : items) {
    if (item.name.empty()) continue;
    if (!seen.insert(item.name).second)
      ctx.error(ctx.source_of(fmt::format("[{}.{}].name", section, item.name)),
                fmt::format("[{}.{}]", section, item.name), fmt::format("the name \"{}\" is used twice", item.name));
  }
}

/// Cross-section checks that no single section can make.
void check_design(Context& ctx, const Design& d)
{
  check_unique_names(ctx, d.fibers, "fiber");
  check_unique_names(ctx, d.targets, "target");
  check_unique_names(ctx, d.tracking_curves, "tracking_curve");
  check_unique_names(ctx, d.fixed, "fixed");
  if (d.optimize.strategy == Strategy::sequential)
    for (const Target& t : d.targets)
      if (!t.actuators.empty()) {
        const std::string key = fmt::format("[target.{}].actuators", t.name);
        ctx.error(ctx.source_of(key), key,
                  "the sequential strategy assigns fiber k to target k; remove the key or use \"simultaneous\"");
      }
  if (d.mold.block.wall < d.export_.min_wall)
    ctx.error(ctx.source_of("[mold].wall"), "[mold].wall",
              fmt::format("{} mm is below the printer's minimum wall [export].min_wall = {} mm",
                          d.mold.block.wall / units::mm, d.export_.min_wall / units::mm));
}

/// Section tables of the root, or null when absent; reports a section of the wrong type.
const toml::table* section_table(Context& ctx, const toml::table& root, const std::string& name)
{
  const toml::node* n = root.get(name);
  if (!n) return nullptr;
  if (!n->is_table()) {
    ctx.error(n->source(), "[" + name + "]", fmt::format("must be a table: write [{}] on a line of its own", name));
    return nullptr;
  }
  return n->as_table();
}

void check_sections(Context& ctx, const toml::table& root)
{
  for (auto&& [key, value] : root) {
    const std::string name(key.str());
    if (std::find(kSections.begin(), kSections.end(), name) != kSections.end()) continue;
    std::string message = fmt::format("unknown section [{}]", name);
    if (auto hint = closest_match(name, kSections)) {
      const bool array = std::find(kArraySections.begin(), kArraySections.end(), *hint) != kArraySections.end();
      message += fmt::format("; did you mean {}{}{}?", array ? "[[" : "[", *hint, array ? "]]" : "]");
    } else {
      message += fmt::format("; valid sections: {}", fmt::join(kSections, ", "));
    }
    ctx.error(key.source(), "[" + name + "]", message);
  }
}

Design read_root(Context& ctx, const toml::table& root, const fs::path& file)
{
  check_sections(ctx, root);
  const auto section = [&](const std::string& name) {
    const toml::table* t = section_table(ctx, root, name);
    return Section(ctx, t, "[" + name + "]", t ? t->source() : toml::source_region{});
  };
  Design d;
  d.file = file;
  d.folder = file.parent_path();
  d.design = read_design(section("design"), file);
  d.material = read_material(section("material"));
  d.mesh = read_mesh(section("mesh"));
  d.sim = read_sim(section("sim"));
  d.fixed = read_fixed(ctx, root);
  d.muscle = read_muscle(section("muscle"));
  d.fibers = read_fibers(ctx, root);
  d.tracking_curves = read_tracking_curves(ctx, root);
  for_each_entry(ctx, root, "target", [&](Section s, std::size_t i) {
    d.targets.push_back(read_target(std::move(s), i, d.muscle, d.fibers));
  });
  d.optimize = read_optimize(section("optimize"));
  d.collide = read_collide(section("collide"));
  d.mold = read_mold(section("mold"));
  d.export_ = read_export(section("export"));
  check_design(ctx, d);
  return d;
}

Design parse(std::string_view text, const fs::path& path)
{
  const fs::path file = fs::absolute(path).lexically_normal();
  Context ctx{file, file.parent_path(), {}, {}, {}};
  toml::table root;
  try {
    root = toml::parse(text, file.string());
  } catch (const toml::parse_error& e) {
    std::string message = fmt::format("not valid TOML: {}", e.description());
    // A list or inline table short of a comma or its closing bracket is found where the next thing
    // starts, often a line or more below: name where it was opened.
    const std::string_view what = e.description();
    const bool at_end = what.find("end-of-file") != std::string_view::npos &&
                        (what.find("parsing array") != std::string_view::npos ||
                         what.find("parsing inline table") != std::string_view::npos);
    if (at_end || what.find("expected comma or closing") != std::string_view::npos)
      if (const auto open = unclosed_bracket(
              text, {static_cast<int>(e.source().begin.line), static_cast<int>(e.source().begin.column)})) {
        const bool list = open->bracket == '[';
        message += fmt::format(" (the {} opened at line {}, column {} ", list ? "list" : "inline table", open->at.line,
                               open->at.column);
        message += at_end ? fmt::format("is never closed: its '{}' is missing)", list ? ']' : '}')
                          : fmt::format("is still open here: a ',' between its {} or its closing '{}' is missing)",
                                        list ? "entries" : "keys", list ? ']' : '}');
      }
    ctx.error(e.source(), "", message);
    throw InputError(std::move(ctx.problems));
  }
  Design d = read_root(ctx, root, file);
  if (!ctx.problems.empty()) {
    std::stable_sort(ctx.problems.begin(), ctx.problems.end(),
                     [](const Diagnostic& a, const Diagnostic& b) { return a.line < b.line; });
    throw InputError(std::move(ctx.problems));
  }
  d.values = std::move(ctx.values);
  for (const auto& [key, where] : ctx.sources)
    d.places[key] = {static_cast<int>(where.begin.line), static_cast<int>(where.begin.column)};
  return d;
}

} // namespace

Diagnostic design_problem(const Design& d, const std::string& key, std::string message)
{
  std::pair<int, int> at{0, 0};
  if (auto it = d.places.find(key); it != d.places.end())
    at = it->second;
  else if (auto section = d.places.lower_bound(key + ".");
           section != d.places.end() && section->first.starts_with(key + "."))
    at = section->second; // "[fiber.m1]": its first key written
  return {d.file, at.first, at.second, key, std::move(message)};
}

Design parse_design(std::string_view toml_text, const fs::path& path) { return parse(toml_text, path); }

Design load_design(const fs::path& path)
{
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(Diagnostic{path, 0, 0, "", "design file not found"});
  if (!fs::is_regular_file(path, ec)) throw InputError(Diagnostic{path, 0, 0, "", "not a regular file"});
  std::string text;
  try {
    text = read_file(path);
  } catch (const std::exception& e) {
    throw InputError(Diagnostic{path, 0, 0, "", e.what()});
  }
  return parse(text, path);
}

bool design_key_matches(std::string_view key, std::string_view prefix)
{
  std::string flat;
  for (char c : key)
    if (c != '[' && c != ']') flat += c;
  if (!flat.starts_with(prefix)) return false;
  return flat.size() == prefix.size() || flat[prefix.size()] == '.' || flat[prefix.size()] == '[';
}

} // namespace fibermold

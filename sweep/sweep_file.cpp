#include "sweep/sweep_file.hpp"

#include <algorithm>
#include <cctype>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/input_error.hpp"
#include "design/did_you_mean.hpp"

namespace fibermold {

namespace fs = std::filesystem;

namespace {

class Reader {
public:
  explicit Reader(fs::path file) : file_(std::move(file)) {}

  void error(const toml::node* n, std::string key, std::string message)
  {
    const auto at = n ? n->source().begin : toml::source_position{};
    problems_.push_back(
        {file_, static_cast<int>(at.line), static_cast<int>(at.column), std::move(key), std::move(message)});
  }
  /// Keys of `t` outside `known` are errors, with the closest known one.
  void only(const toml::table& t, const std::string& section, const std::vector<std::string>& known)
  {
    for (const auto& [k, v] : t) {
      const std::string key(k.str());
      if (std::find(known.begin(), known.end(), key) != known.end()) continue;
      std::string message = fmt::format("unknown key '{}' in [{}]", key, section);
      if (auto hint = closest_match(key, known)) message += fmt::format("; did you mean '{}'?", *hint);
      error(&v, fmt::format("[{}].{}", section, key), message);
    }
  }
  /// t[key] when present; a value of the wrong type is an error ("needs <what>").
  template <class T>
  std::optional<T> get(const toml::table& t, const std::string& section, const char* key, const char* what)
  {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    if (auto v = n->value<T>()) return v;
    error(n, fmt::format("[{}].{}", section, key), fmt::format("needs {}", what));
    return std::nullopt;
  }
  /// A list of strings.
  std::vector<std::string> strings(const toml::table& t, const std::string& section, const char* key)
  {
    std::vector<std::string> out;
    const toml::node* n = t.get(key);
    if (!n) return out;
    const toml::array* a = n->as_array();
    for (std::size_t i = 0; a && i < a->size(); ++i)
      if (auto v = a->get(i)->value<std::string>())
        out.push_back(*v);
      else
        a = nullptr;
    if (!a) error(n, fmt::format("[{}].{}", section, key), "needs a list of strings");
    return out;
  }
  std::vector<Diagnostic>& problems() { return problems_; }

private:
  fs::path file_;
  std::vector<Diagnostic> problems_;
};

/// Letters, digits, '-', '_', '.' (and ':', ',' for Slurm values); not starting with '.'.
bool plain(const std::string& s, bool slurm)
{
  if (s.empty()) return slurm;
  return s[0] != '.' && std::all_of(s.begin(), s.end(), [&](unsigned char c) {
           return std::isalnum(c) || c == '-' || c == '_' || c == '.' || (slurm && (c == ':' || c == ','));
         });
}

std::string toml_text(const toml::node& n)
{
  std::ostringstream out;
  n.visit([&](const auto& v) { out << v; });
  return out.str();
}

/// One entry of `[axes]` (a list of values) or of a `[[case]]` (one value); its key is a
/// design-file key ("mold.wall").
std::vector<SweepValue> values_of(const std::string& key, const toml::node& v, Reader& r, const std::string& where,
                                  bool list)
{
  std::vector<SweepValue> out;
  const auto at = v.source().begin;
  if (key.find('.') == std::string::npos) {
    r.error(&v, fmt::format("{}.\"{}\"", where, key),
            "a design-file key names its section, e.g. \"mold.wall\" or \"fiber.m1.points\" (quoted)");
    return out;
  }
  const int line = static_cast<int>(at.line), column = static_cast<int>(at.column);
  if (!list) return {{key, toml_text(v), line, column}};
  const toml::array* a = v.as_array();
  if (!a || a->empty()) {
    r.error(&v, fmt::format("{}.\"{}\"", where, key), "needs a non-empty list of values, e.g. [3, 4]");
    return out;
  }
  for (const toml::node& value : *a)
    out.push_back({key, toml_text(value), static_cast<int>(value.source().begin.line),
                   static_cast<int>(value.source().begin.column)});
  return out;
}

/// [sweep]: the base design and the sweep's name.
void read_sweep_section(Reader& r, const toml::table& root, SweepFile& s)
{
  const toml::table* sweep = root["sweep"].as_table();
  if (!sweep) {
    r.error(nullptr, "[sweep]", "missing: [sweep] design = \"path/to/design.toml\" names the base design");
  } else {
    r.only(*sweep, "sweep", {"design", "name"});
    if (auto design = r.get<std::string>(*sweep, "sweep", "design", "the base design's path as a string")) {
      s.base =
          (fs::path(*design).is_absolute() ? fs::path(*design) : s.file.parent_path() / *design).lexically_normal();
      std::error_code ec;
      if (!fs::is_regular_file(s.base, ec))
        r.error(sweep->get("design"), "[sweep].design", "file not found: " + s.base.string());
    } else if (!sweep->get("design")) {
      r.error(sweep, "[sweep].design", "missing: the base design's path, e.g. design = \"design.toml\"");
    }
    s.name = r.get<std::string>(*sweep, "sweep", "name", "a string").value_or(s.file.stem().string());
    if (!plain(s.name, false)) {
      r.error(sweep->get("name"), "[sweep].name",
              fmt::format("\"{}\" cannot name a folder: use letters, digits, '-', '_' and '.'", s.name));
      s.name = "sweep";
    }
  }
}

/// [axes] (their full product) or [[case]]s: the designs' values.
void read_cases(Reader& r, const toml::table& root, SweepFile& s)
{
  const toml::table* axes = root["axes"].as_table();
  const toml::array* cases = root["case"].as_array();
  if (axes && cases)
    r.error(root.get("case"), "[[case]]", "give either [axes] (their full product) or [[case]]s, not both");
  if (axes) {
    std::vector<std::vector<SweepValue>> product{{}};
    for (const auto& [k, v] : *axes) {
      std::vector<SweepValue> values = values_of(std::string(k.str()), v, r, "[axes]", true);
      if (values.empty()) continue;
      s.axes.push_back(values.front().key);
      std::vector<std::vector<SweepValue>> next;
      for (const auto& partial : product)
        for (const SweepValue& value : values) {
          next.push_back(partial);
          next.back().push_back(value);
        }
      product = std::move(next);
    }
    s.cases = std::move(product);
  } else if (cases) {
    for (const toml::node& c : *cases) {
      const toml::table* t = c.as_table();
      if (!t) continue;
      s.cases.emplace_back();
      for (const auto& [k, v] : *t) {
        std::vector<SweepValue> one = values_of(std::string(k.str()), v, r, "[[case]]", false);
        s.cases.back().insert(s.cases.back().end(), one.begin(), one.end());
      }
      for (const SweepValue& v : s.cases.back())
        if (std::find(s.axes.begin(), s.axes.end(), v.key) == s.axes.end()) s.axes.push_back(v.key);
    }
  } else {
    s.cases = {{}};
  }
}

/// [restarts]: more starts of each case, the fibers' routes moved at random.
void read_restarts(Reader& r, const toml::table& root, SweepFile& s)
{
  if (const toml::table* restarts = root["restarts"].as_table()) {
    r.only(*restarts, "restarts", {"count", "seed", "amplitude", "fibers"});
    const auto count = r.get<std::int64_t>(*restarts, "restarts", "count", "a whole number in [1, 1000]");
    if (count && (*count < 1 || *count > 1000))
      r.error(restarts->get("count"), "[restarts].count", "needs a whole number in [1, 1000]");
    else if (count)
      s.restarts.count = static_cast<int>(*count);
    else if (!restarts->get("count"))
      r.error(restarts, "[restarts].count", "missing: how many starts, e.g. count = 4");
    s.restarts.seed =
        static_cast<std::uint64_t>(r.get<std::int64_t>(*restarts, "restarts", "seed", "a whole number").value_or(1));
    s.restarts.amplitude = r.get<double>(*restarts, "restarts", "amplitude", "a length in mm").value_or(2.0);
    if (!(s.restarts.amplitude > 0))
      r.error(restarts->get("amplitude"), "[restarts].amplitude", "needs a length in mm above 0");
    s.restarts.fibers = r.strings(*restarts, "restarts", "fibers");
    if (const toml::node* f = restarts->get("fibers")) s.restarts.line = static_cast<int>(f->source().begin.line);
    if (s.restarts.count > 0) s.axes.push_back("restart");
  }
}

/// [slurm]: the job arrays' defaults.
void read_slurm(Reader& r, const toml::table& root, SweepFile& s)
{
  if (const toml::table* slurm = root["slurm"].as_table()) {
    r.only(*slurm, "slurm", {"partition", "time", "cpus_per_task", "extra"});
    s.slurm.partition = r.get<std::string>(*slurm, "slurm", "partition", "a partition name").value_or("");
    s.slurm.time =
        r.get<std::string>(*slurm, "slurm", "time", "a time limit as Slurm writes it, e.g. \"02:00:00\"").value_or("");
    s.slurm.cpus_per_task =
        static_cast<int>(r.get<std::int64_t>(*slurm, "slurm", "cpus_per_task", "a whole number").value_or(0));
    if (slurm->get("cpus_per_task") && s.slurm.cpus_per_task < 1)
      r.error(slurm->get("cpus_per_task"), "[slurm].cpus_per_task", "needs a whole number of at least 1");
    // They go into the job script's #SBATCH lines.
    for (const auto& [key, value] : {std::pair{"partition", s.slurm.partition}, std::pair{"time", s.slurm.time}})
      if (!plain(value, true))
        r.error(slurm->get(key), fmt::format("[slurm].{}", key), fmt::format("\"{}\" is not a Slurm {}", value, key));
    s.slurm.extra = r.strings(*slurm, "slurm", "extra");
  }
}

} // namespace

bool is_slurm_word(const std::string& value) { return plain(value, true); }

SweepFile load_sweep(const fs::path& path)
{
  SweepFile s;
  s.file = fs::absolute(path).lexically_normal();
  toml::table root;
  try {
    root = toml::parse_file(s.file.string());
  } catch (const toml::parse_error& e) {
    throw InputError(Diagnostic{s.file, static_cast<int>(e.source().begin.line),
                                static_cast<int>(e.source().begin.column), "", std::string(e.description())});
  } catch (const std::exception&) {
    throw InputError(Diagnostic{s.file, 0, 0, "", "cannot read the sweep file"});
  }
  Reader r(s.file);
  r.only(root, "", {"sweep", "axes", "case", "restarts", "slurm"});
  for (const char* table : {"sweep", "axes", "restarts", "slurm"})
    if (const toml::node* n = root.get(table); n && !n->is_table())
      r.error(n, table, fmt::format("needs a table: [{}]", table));
  if (const toml::node* n = root.get("case"); n && !n->is_array_of_tables())
    r.error(n, "case", "needs tables: [[case]]");

  read_sweep_section(r, root, s);
  read_cases(r, root, s);
  read_restarts(r, root, s);
  read_slurm(r, root, s);
  if (!r.problems().empty()) throw InputError(std::move(r.problems()));
  return s;
}

} // namespace fibermold

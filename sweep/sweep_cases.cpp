#include "sweep/sweep_cases.hpp"

#include <algorithm>
#include <random>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/input_error.hpp"
#include "design/design_file.hpp"
#include "make/content_hash.hpp"

namespace fibermold {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> split(const std::string& key)
{
  std::vector<std::string> out{""};
  for (char c : key)
    if (c == '.')
      out.emplace_back();
    else
      out.back().push_back(c);
  return out;
}

/// Puts `value` at design-file key `key` ("mold.wall", "fiber.m1.points"); a message when it cannot.
std::string put(toml::table& design, const std::string& key, const toml::node& value)
{
  const std::vector<std::string> parts = split(key);
  const std::string& section = parts.front();
  const auto& sections = design_sections();
  if (std::find(sections.begin(), sections.end(), section) == sections.end())
    return fmt::format("unknown section '{}'; valid sections: {}", section, fmt::join(sections, ", "));
  toml::table* table = nullptr;
  std::size_t field = 1;
  if (is_array_section(section)) {
    if (parts.size() < 3) return fmt::format("name the [[{0}]]: \"{0}.<name>.<key>\"", section);
    const std::string name = fmt::format("{}", fmt::join(parts.begin() + 1, parts.end() - 1, "."));
    std::vector<std::string> names;
    if (toml::array* list = design[section].as_array())
      for (toml::node& element : *list)
        if (toml::table* t = element.as_table()) {
          names.push_back(t->get("name") ? (*t)["name"].value_or(std::string{}) : "");
          if (names.back() == name) table = t;
        }
    if (!table)
      return fmt::format("the base design has no [[{}]] named '{}' (it has: {})", section, name,
                         fmt::join(names, ", "));
    field = parts.size() - 1;
  } else {
    if (parts.size() < 2 || parts.back().empty()) return fmt::format("name a key of [{}]", section);
    if (!design[section].as_table()) design.insert_or_assign(section, toml::table{});
    table = design[section].as_table();
    for (; field + 1 < parts.size(); ++field) {
      if (!(*table)[parts[field]].as_table()) table->insert_or_assign(parts[field], toml::table{});
      table = (*table)[parts[field]].as_table();
    }
  }
  value.visit([&](const auto& v) { table->insert_or_assign(parts[field], v); });
  return {};
}

/// A restart: each chosen fiber's interior control points moved by up to `amplitude` mm, uniformly
/// in a ball; end points stay.
void restart(toml::table& design, const SweepRestarts& r, int index)
{
  std::mt19937_64 random(r.seed * 1000003u + static_cast<std::uint64_t>(index));
  const auto uniform = [&] { return static_cast<double>(random() >> 11) * 0x1.0p-53 * 2 - 1; };
  toml::array* fibers = design["fiber"].as_array();
  for (std::size_t k = 0; fibers && k < fibers->size(); ++k) {
    toml::table* fiber = fibers->get(k)->as_table();
    if (!fiber) continue;
    const std::string name = (*fiber)["name"].value_or(std::string{});
    if (!r.fibers.empty() && std::find(r.fibers.begin(), r.fibers.end(), name) == r.fibers.end()) continue;
    toml::array* points = (*fiber)["points"].as_array();
    for (std::size_t i = 1; points && i + 1 < points->size(); ++i) {
      toml::array* p = points->get(i)->as_array();
      if (!p || p->size() != 3) continue;
      double d[3];
      do {
        for (double& x : d) x = uniform();
      } while (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 1);
      for (std::size_t c = 0; c < 3; ++c) {
        const double x = p->get(c)->value<double>().value_or(0) + r.amplitude * d[c];
        p->replace(p->begin() + static_cast<std::ptrdiff_t>(c), std::round(x * 1e6) / 1e6);
      }
    }
  }
}

/// Relative file paths made absolute against the base design's folder, so that the case's design
/// works from its own folder.
void absolute_paths(toml::table& design, const fs::path& folder)
{
  const auto fix = [&](toml::table* t) {
    if (!t) return;
    if (auto path = (*t)["surface"].value<std::string>(); path && fs::path(*path).is_relative())
      t->insert_or_assign("surface", (folder / *path).lexically_normal().string());
  };
  fix(design["design"].as_table());
  if (toml::array* targets = design["target"].as_array())
    for (toml::node& t : *targets) fix(t.as_table());
}

/// The sweep file's line for a problem the design file reports at `key` ("[mold].wall").
Diagnostic at_sweep_line(const SweepFile& sweep, const std::vector<SweepValue>& values, const Diagnostic& d,
                         std::size_t case_index)
{
  std::string key = d.key;
  std::erase_if(key, [](char c) { return c == '[' || c == ']'; });
  for (const SweepValue& v : values)
    if (!key.empty() && (key == v.key || key.starts_with(v.key + ".") || v.key.starts_with(key + ".")))
      return {sweep.file, v.line, v.column, fmt::format("\"{}\" = {}", v.key, v.value), d.message};
  return {sweep.file, 0, 0, fmt::format("case {}", case_index + 1), fmt::format("{}: {}", d.key, d.message)};
}

} // namespace

std::vector<SweepCase> expand_sweep(const SweepFile& sweep)
{
  const Design base_design = load_design(sweep.base); // the base's own problems, at its own lines
  for (const std::string& name : sweep.restarts.fibers)
    if (std::none_of(base_design.fibers.begin(), base_design.fibers.end(),
                     [&](const Fiber& f) { return f.name == name; }))
      throw InputError(Diagnostic{sweep.file, sweep.restarts.line, 0, "[restarts].fibers",
                                  fmt::format("the base design has no [[fiber]] named '{}'", name)});
  const toml::table base = toml::parse_file(sweep.base.string());
  std::vector<SweepCase> out;
  std::vector<Diagnostic> problems;
  std::set<std::string> seen_problems;
  const auto problem = [&](Diagnostic d) {
    if (seen_problems.insert(d.to_string()).second) problems.push_back(std::move(d));
  };
  const int restarts = std::max(1, sweep.restarts.count);
  for (std::size_t c = 0; c < sweep.cases.size(); ++c)
    for (int r = 0; r < restarts; ++r) {
      toml::table design = base;
      SweepCase one;
      std::vector<std::string> values(sweep.axes.size());
      bool ok = true;
      for (const SweepValue& v : sweep.cases[c]) {
        const toml::parse_result parsed = toml::parse("x = " + v.value);
        if (const std::string why = put(design, v.key, *parsed["x"].node()); !why.empty()) {
          problem({sweep.file, v.line, v.column, fmt::format("\"{}\"", v.key), why});
          ok = false;
        }
        values[static_cast<std::size_t>(std::find(sweep.axes.begin(), sweep.axes.end(), v.key) - sweep.axes.begin())] =
            v.value;
      }
      if (!ok) continue;
      if (r > 0) restart(design, sweep.restarts, r);
      if (sweep.restarts.count > 0) values.back() = std::to_string(r);
      if (!design["design"]["name"]) design["design"].as_table()->insert_or_assign("name", base_design.design.name);
      absolute_paths(design, sweep.base.parent_path());
      std::ostringstream text;
      text << "# Made by fibermold sweep from the base design " << sweep.base.string() << "\n" << design << "\n";
      one.design = text.str();
      try {
        parse_design(one.design, sweep.base);
      } catch (const InputError& e) {
        for (const Diagnostic& d : e.diagnostics()) problem(at_sweep_line(sweep, sweep.cases[c], d, c));
        continue;
      }
      one.id = hash_bytes(one.design).substr(0, 10);
      one.values = std::move(values);
      if (std::any_of(out.begin(), out.end(), [&](const SweepCase& o) { return o.id == one.id; }))
        problem({sweep.file, sweep.cases[c].empty() ? 0 : sweep.cases[c].front().line, 0, fmt::format("case {}", c + 1),
                 "makes the same design as an earlier case"});
      out.push_back(std::move(one));
    }
  if (!problems.empty()) throw InputError(std::move(problems));
  return out;
}

} // namespace fibermold

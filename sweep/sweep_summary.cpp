#include "sweep/sweep_summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"

namespace fibermold {

namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

std::optional<Json> json_file(const fs::path& file)
{
  std::error_code ec;
  if (!fs::exists(file, ec)) return std::nullopt;
  try {
    return Json::parse(read_file(file));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

/// One case's row: column → value (numbers as numbers, words as words, absent cells absent).
struct Row {
  std::map<std::string, double> numbers;
  std::map<std::string, std::string> texts; ///< "optimizer": how it stopped; "report": the case's report.html
};

/// An axis value as a person reads it: a TOML string without its quotes ("dragon-skin-10", not '"dragon-skin-10"').
std::string shown(const std::string& toml)
{
  const bool quoted = toml.size() >= 2 && (toml.front() == '"' || toml.front() == '\'') && toml.back() == toml.front();
  return quoted ? toml.substr(1, toml.size() - 2) : toml;
}

std::string csv_cell(std::string s)
{
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string html_escape(const std::string& s)
{
  std::string out;
  for (char c : s)
    out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : c == '"' ? "&quot;" : std::string(1, c);
  return out;
}

std::string number(double v) { return fmt::format("{:.6g}", v); }

/// An SVG scatter plot of `y` against `x`, labelled by case.
std::string scatter(const std::string& x_name, const std::vector<double>& x, const std::string& y_name,
                    const std::vector<double>& y, const std::vector<std::string>& labels)
{
  double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = 0, y1 = -HUGE_VAL;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::isfinite(y[i])) x0 = std::min(x0, x[i]), x1 = std::max(x1, x[i]), y1 = std::max(y1, y[i]);
  if (!(x1 >= x0) || !(y1 > 0)) return {};
  if (x1 == x0) x0 -= 1, x1 += 1;
  const double W = 520, H = 300, L = 60, B = 40, T = 15, R = 20;
  const auto px = [&](double v) { return L + (v - x0) / (x1 - x0) * (W - L - R); };
  const auto py = [&](double v) { return H - B - (v - y0) / (y1 * 1.1 - y0) * (H - B - T); };
  std::string svg =
      fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" class=\"plot\">", W, H);
  svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"#444\"/><line x1=\"{0}\" y1=\"{3}\" "
                     "x2=\"{0}\" y2=\"{1}\" stroke=\"#444\"/>",
                     L, H - B, W - R, T);
  for (int k = 0; k <= 4; ++k) {
    const double xv = x0 + (x1 - x0) * k / 4, yv = y1 * 1.1 * k / 4;
    svg += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"11\" text-anchor=\"middle\">{}</text>", px(xv), H - B + 15,
                       number(xv));
    svg += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"11\" text-anchor=\"end\">{}</text>", L - 5, py(yv) + 4,
                       number(yv));
  }
  svg += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"12\" text-anchor=\"middle\">{}</text>", (L + W - R) / 2,
                     H - 5, html_escape(x_name));
  svg += fmt::format(
      "<text x=\"12\" y=\"{}\" font-size=\"12\" transform=\"rotate(-90 12 {})\" text-anchor=\"middle\">{}</text>",
      (H - B + T) / 2, (H - B + T) / 2, html_escape(y_name));
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::isfinite(y[i]))
      svg += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" fill=\"#1f77b4\"><title>{}: {}</title></circle>",
                         px(x[i]), py(y[i]), html_escape(labels[i]), number(y[i]));
  return svg + "</svg>";
}

} // namespace

namespace {

/// The summary's table: a row per case, its columns, and the best cases per target.
struct Summary {
  std::vector<std::string> targets, pressure_columns, columns;
  std::vector<Row> rows;
  /// per target: the cases of least RMSE after collide (several where they tie: cases that share an optimization)
  std::map<std::string, std::vector<std::size_t>> best;

  bool is_best(const std::string& target, std::size_t i) const
  {
    const auto b = best.find(target);
    return b != best.end() && std::find(b->second.begin(), b->second.end(), i) != b->second.end();
  }
  std::string best_for(std::size_t i) const
  {
    std::string s;
    for (const auto& [t, cases] : best)
      if (is_best(t, i)) s += (s.empty() ? "" : " ") + t;
    return s;
  }
  /// A cell as text: a number at 6 significant figures, a word as it is, else empty.
  std::string cell(std::size_t i, const std::string& column) const
  {
    const Row& r = rows[i];
    if (const auto n = r.numbers.find(column); n != r.numbers.end()) return number(n->second);
    if (const auto t = r.texts.find(column); t != r.texts.end()) return t->second;
    return {};
  }
};

void add_column(std::vector<std::string>& columns, const std::string& c)
{
  if (std::find(columns.begin(), columns.end(), c) == columns.end()) columns.push_back(c);
}

/// A case's figures from its built outputs.
Row case_row(const SweepPlan& plan, const fs::path& dir, Summary& s)
{
  Row row;
  // A stage's outputs count only while it is built (its stamp is there): after a failed rerun
  // they are last time's.
  const auto built = [&](const std::string& stage) {
    std::error_code ec;
    return fs::exists(Runner::stamp_path(dir, stage), ec);
  };
  try {
    if (const auto report = json_file(dir / "collide" / "report.json");
        built("collide") && report && report->contains("targets") && (*report)["targets"].is_object())
      for (const auto& [name, t] : (*report)["targets"].items()) {
        add_column(s.targets, name);
        if (t["after"]["rmse_mm"].is_number()) row.numbers[name + " RMSE mm"] = t["after"]["rmse_mm"].get<double>();
        if (t["after"]["max_error_mm"].is_number())
          row.numbers[name + " max mm"] = t["after"]["max_error_mm"].get<double>();
        // The turn's error, where a tracking curve's orientation is tracked: a twist shows there.
        if (t["after"].contains("orientation_rms_deg") && t["after"]["orientation_rms_deg"].is_number())
          row.numbers[name + " turn RMS deg"] = t["after"]["orientation_rms_deg"].get<double>();
        // A pose target's figure: how much of its angle its least-turned region turned (a new user's sweep
        // over max_pressure marked best on RMSE the case that turned 36.6° of 45°, not the one at 38.4°).
        for (const Json& pose : t.value("poses", Json::array()))
          if (pose.contains("rotation_reached_percent") && pose["rotation_reached_percent"].is_number()) {
            const double reached = pose["rotation_reached_percent"].get<double>();
            const auto [at, added] = row.numbers.try_emplace(name + " turn reached %", reached);
            if (!added) at->second = std::min(at->second, reached);
          }
      }
    if (const auto report = json_file(dir / "optimize" / "report.json");
        built("optimize") && report && (*report)["termination"].is_string())
      row.texts["optimizer"] = (*report)["termination"].get<std::string>();
    if (const auto fibers = json_file(dir / "collide" / "fibers.json"); built("collide") && fibers)
      for (const Json& f : (*fibers)["fibers"])
        for (const auto& [target, kpa] : f["pressure_kPa"].items()) {
          const std::string column = fmt::format("{} {} kPa", f["name"].get<std::string>(), target);
          add_column(s.pressure_columns, column);
          if (kpa.is_number()) row.numbers[column] = kpa.get<double>();
        }
    if (const auto molds = json_file(dir / "molds" / "report.json"); built("molds") && molds) {
      double silicone = 0;
      for (const auto& [shot, m] : (*molds)["shots"].items()) silicone += m["silicone_volume_mL"].get<double>();
      row.numbers["silicone mL"] = silicone;
      row.numbers["mold parts"] = static_cast<double>((*molds)["parts"].size());
    }
  } catch (const std::exception&) {
    // An output of another version: its cells stay empty.
  }
  for (const std::string& stage : plan.stages)
    if (const auto stamp = json_file(Runner::stamp_path(dir, stage)); stamp && (*stamp)["seconds"].is_number())
      row.numbers[stage + " s"] = (*stamp)["seconds"].get<double>();
  if (std::error_code ec; built("export") && fs::exists(dir / "export" / "report.html", ec))
    row.texts["report"] = (plan.case_dir({}, dir.filename().string()) / "export" / "report.html").generic_string();
  return row;
}

Summary summarize(const SweepPlan& plan, const fs::path& build_dir)
{
  Summary s;
  for (const SweepCase& c : plan.cases) s.rows.push_back(case_row(plan, plan.case_dir(build_dir, c.id), s));
  for (const std::string& t : s.targets)
    s.columns.insert(s.columns.end(), {t + " RMSE mm", t + " max mm", t + " turn RMS deg", t + " turn reached %"});
  s.columns.insert(s.columns.end(), s.pressure_columns.begin(), s.pressure_columns.end());
  s.columns.insert(s.columns.end(), {"optimizer", "silicone mL", "mold parts"});
  for (const std::string& stage : plan.stages) s.columns.push_back(stage + " s");
  s.columns.push_back("report");
  std::erase_if(s.columns, [&](const std::string& col) {
    return std::none_of(s.rows.begin(), s.rows.end(),
                        [&](const Row& r) { return r.numbers.contains(col) || r.texts.contains(col); });
  });
  for (const std::string& t : s.targets) {
    double least = HUGE_VAL;
    for (const Row& r : s.rows)
      if (auto it = r.numbers.find(t + " RMSE mm"); it != r.numbers.end()) least = std::min(least, it->second);
    for (std::size_t i = 0; i < s.rows.size(); ++i)
      if (auto it = s.rows[i].numbers.find(t + " RMSE mm"); it != s.rows[i].numbers.end() && it->second == least)
        s.best[t].push_back(i);
  }
  return s;
}

std::string summary_csv(const SweepPlan& plan, const Summary& s)
{
  std::string csv = "case";
  for (const std::string& a : plan.axes) csv.append(",").append(csv_cell(a));
  for (const std::string& col : s.columns) csv.append(",").append(csv_cell(col));
  csv += ",best for\n";
  for (std::size_t i = 0; i < s.rows.size(); ++i) {
    csv += plan.cases[i].id;
    for (const std::string& v : plan.cases[i].values) csv.append(",").append(csv_cell(shown(v)));
    for (const std::string& col : s.columns) csv.append(",").append(csv_cell(s.cell(i, col)));
    csv.append(",").append(csv_cell(s.best_for(i))).append("\n");
  }
  return csv;
}

/// Error against the first axis whose values are all numbers (else against the case's index).
std::pair<std::string, std::vector<double>> error_axis(const SweepPlan& plan, std::size_t rows)
{
  std::vector<double> x(rows);
  for (std::size_t i = 0; i < rows; ++i) x[i] = static_cast<double>(i + 1);
  for (std::size_t a = 0; a < plan.axes.size(); ++a) {
    std::vector<double> values;
    for (const SweepCase& c : plan.cases) {
      char* end = nullptr;
      const double v = std::strtod(c.values[a].c_str(), &end);
      if (c.values[a].empty() || *end) break;
      values.push_back(v);
    }
    if (values.size() == rows) return {plan.axes[a], values};
  }
  return {"case", x};
}

std::string summary_html(const SweepPlan& plan, const Summary& s)
{
  std::string html =
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>fibermold sweep " + html_escape(plan.name) +
      "</title><style>body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse}td,th{border:1px solid "
      "#ccc;"
      "padding:3px 8px;text-align:right}th{background:#f3f3f3}td.best{background:#d9f2d9;font-weight:bold}"
      "td.text{text-align:left;font-family:monospace}</style></head><body>\n";
  html += fmt::format(
      "<h1>Sweep {}</h1><p>{} case(s) from <code>{}</code>. The best cases per target (least RMSE after collide) "
      "are marked green; <em>turn reached %</em> is the share of a pose target's angle that its least-turned region "
      "turned, and <em>optimizer</em> how the optimization ended (README.txt of the case says what to do where it "
      "did not converge).</p>\n<table><tr><th>case</th>",
      html_escape(plan.name), plan.cases.size(), html_escape(plan.sweep_file.string()));
  for (const std::string& a : plan.axes) html += "<th>" + html_escape(a) + "</th>";
  for (const std::string& col : s.columns) html += "<th>" + html_escape(col) + "</th>";
  html += "</tr>\n";
  for (std::size_t i = 0; i < s.rows.size(); ++i) {
    html += "<tr><td class=\"text\">" + plan.cases[i].id + "</td>";
    for (const std::string& v : plan.cases[i].values) html += "<td class=\"text\">" + html_escape(shown(v)) + "</td>";
    for (const std::string& col : s.columns) {
      const bool is_best = std::any_of(s.targets.begin(), s.targets.end(),
                                       [&](const std::string& t) { return col == t + " RMSE mm" && s.is_best(t, i); });
      const std::string cell = html_escape(s.cell(i, col));
      html += std::string(is_best                         ? "<td class=\"best\">"
                          : s.rows[i].texts.contains(col) ? "<td class=\"text\">"
                                                          : "<td>") +
              (col == "report" && !cell.empty() ? "<a href=\"" + cell + "\">report.html</a>" : cell) + "</td>";
    }
    html += "</tr>\n";
  }
  html += "</table>\n";
  const auto [x_name, x] = error_axis(plan, s.rows.size());
  std::vector<std::string> labels;
  for (const SweepCase& c : plan.cases) labels.push_back(c.id);
  for (const std::string& t : s.targets) {
    std::vector<double> y;
    for (const Row& r : s.rows) y.push_back(r.numbers.contains(t + " RMSE mm") ? r.numbers.at(t + " RMSE mm") : NAN);
    html += "<h2>" + html_escape(t) + ": RMSE against " + html_escape(x_name) + "</h2>\n" +
            scatter(x_name, x, t + " RMSE mm", y, labels) + "\n";
  }
  return html + "</body></html>\n";
}

} // namespace

void write_sweep_summary(const SweepPlan& plan, const fs::path& build_dir)
{
  const Summary s = summarize(plan, build_dir);
  write_file_atomic(build_dir / "summary.csv", summary_csv(plan, s));
  write_file_atomic(build_dir / "summary.html", summary_html(plan, s));
}

} // namespace fibermold

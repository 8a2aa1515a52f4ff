// The rules of the house that the source tree itself must keep (docs/architecture.md): the module
// order, no folder holding the bulk of the code, short functions, third-party headers out of the
// public ones, nothing cited from outside the repository, every file formatted and no line over 120
// columns, units converted through core/units.hpp.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

namespace fibermold {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = FIBERMOLD_SOURCE_DIR;

/// The module folders and what each may include (docs/architecture.md, "Modules").
const std::map<std::string, std::set<std::string>>& allowed()
{
  static const std::map<std::string, std::set<std::string>> deps{
      {"core", {}},
      {"mesh", {"core"}},
      {"sim", {"core", "mesh"}},
      {"optimize", {"core", "mesh", "sim"}},
      {"molds", {"core", "mesh"}},
      {"export", {"core", "mesh", "molds"}},
      {"design", {"core", "mesh", "sim", "optimize", "molds"}},
      {"make", {"core", "mesh", "sim", "optimize", "molds", "design"}},
      {"stages", {"core", "mesh", "sim", "optimize", "molds", "export", "design", "make"}},
      {"sweep", {"core", "mesh", "sim", "optimize", "molds", "design", "make"}},
      {"cli", {"core", "mesh", "sim", "optimize", "molds", "export", "design", "make", "stages", "sweep"}},
  };
  return deps;
}

std::string text_of(const fs::path& p)
{
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Adds every .cpp and .hpp under `folder` to `out`.
void add_sources(const fs::path& folder, std::vector<fs::path>& out)
{
  for (const auto& e : fs::recursive_directory_iterator(folder))
    if (e.path().extension() == ".cpp" || e.path().extension() == ".hpp") out.push_back(e.path());
}

/// Every .cpp and .hpp of the module folders.
std::vector<fs::path> module_sources()
{
  std::vector<fs::path> out;
  for (const auto& [module, deps] : allowed()) add_sources(kSource / module, out);
  return out;
}

std::string module_of(const fs::path& p) { return fs::relative(p, kSource).begin()->string(); }

TEST(Architecture, IncludesFollowTheModuleOrder)
{
  const std::regex include(R"re(#include "([a-z_]+)/)re");
  int checked = 0;
  for (const fs::path& file : module_sources()) {
    const std::string module = module_of(file), text = text_of(file);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), include); it != std::sregex_iterator(); ++it) {
      const std::string to = (*it)[1];
      if (to == module) continue;
      ++checked;
      EXPECT_TRUE(allowed().at(module).contains(to))
          << fs::relative(file, kSource) << " includes " << to << "/: against the module order";
    }
  }
  EXPECT_GT(checked, 200);
}

/// The concepts of one folder (a .hpp with its .cpp) include each other without a cycle: a file
/// that needs another's header while that one needs its own is one concept split in two, or a
/// third one hidden in them.
TEST(Architecture, NoConceptsOfAFolderIncludeEachOtherInACycle)
{
  const std::regex include(R"re(#include "([a-z_]+)/([a-z0-9_]+)\.hpp")re");
  std::map<std::string, std::map<std::string, std::set<std::string>>> graphs; // folder → concept → included
  for (const fs::path& file : module_sources()) {
    const std::string module = module_of(file), from = file.stem().string(), text = text_of(file);
    auto& graph = graphs[module];
    graph[from];
    for (auto it = std::sregex_iterator(text.begin(), text.end(), include); it != std::sregex_iterator(); ++it)
      if ((*it)[1] == module && (*it)[2] != from) graph[from].insert((*it)[2]);
  }
  for (const auto& [module, graph] : graphs) {
    std::map<std::string, int> state; // 1 on the path, 2 done
    std::vector<std::string> path;
    std::function<void(const std::string&)> visit = [&](const std::string& c) {
      state[c] = 1;
      path.push_back(c);
      for (const std::string& next : graph.at(c)) {
        if (!graph.contains(next)) continue; // a header without a concept of its own here
        if (state[next] == 1) {
          std::string cycle;
          for (auto i = std::find(path.begin(), path.end(), next); i != path.end(); ++i) cycle += *i + " → ";
          ADD_FAILURE() << module << "/: the includes go round " << cycle << next;
        } else if (state[next] == 0) {
          visit(next);
        }
      }
      path.pop_back();
      state[c] = 2;
    };
    for (const auto& [concept_name, included] : graph)
      if (state[concept_name] == 0) visit(concept_name);
  }
  EXPECT_GE(graphs.size(), allowed().size());
}

TEST(Architecture, NoFolderHoldsAQuarterOfTheCode)
{
  std::map<std::string, int> lines;
  int total = 0;
  for (const fs::path& file : module_sources()) {
    const std::string text = text_of(file);
    const int n = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
    lines[module_of(file)] += n;
    total += n;
  }
  ASSERT_GT(total, 10000);
  for (const auto& [module, n] : lines)
    EXPECT_LE(n, total / 4) << module << "/ holds " << n << " of " << total << " lines (" << 100.0 * n / total << " %)";
}

/// Functions defined at namespace scope open with "{" and close with "}" alone on a line (the
/// house's clang-format style): the lines between them, counted.
TEST(Architecture, NoFunctionIsLongerThanAHundredLines)
{
  int functions = 0;
  for (const fs::path& file : module_sources()) {
    std::ifstream in(file);
    std::string line, signature, previous;
    int start = 0, number = 0;
    while (std::getline(in, line)) {
      ++number;
      if (line == "{")
        start = number, signature = previous;
      else if (line == "}" && start > 0) {
        ++functions;
        EXPECT_LE(number - start + 1, 100) << fs::relative(file, kSource) << ":" << start << ": " << signature << " is "
                                           << number - start + 1 << " lines";
        start = 0;
      }
      previous = line;
    }
  }
  EXPECT_GT(functions, 300);
}

/// A header in a module's detail/ folder is private: for the .cpp files that need it.
bool is_private(const fs::path& file) { return file.parent_path().filename() == "detail"; }

/// CGAL, OpenVDB, TetGen, assimp and the Hershey font library stay inside the .cpp files that need
/// them (and the private headers they share).
TEST(Architecture, PublicHeadersIncludeNoGeometryLibrary)
{
  const std::regex third_party(R"re(#include <(CGAL|openvdb|tetgen|assimp|hersheyfont)[/.>])re");
  for (const fs::path& file : module_sources()) {
    if (file.extension() != ".hpp" || is_private(file)) continue;
    const std::string text = text_of(file);
    std::smatch m;
    EXPECT_FALSE(std::regex_search(text, m, third_party)) << fs::relative(file, kSource) << " includes " << m.str();
  }
}

/// Only .cpp files include a private header, so that what it includes never reaches a public one.
TEST(Architecture, OnlySourceFilesIncludePrivateHeaders)
{
  const std::regex private_include(R"re(#include "[a-z_]+/detail/[a-z0-9_]+\.hpp")re");
  int included = 0;
  for (const fs::path& file : module_sources()) {
    const std::string text = text_of(file);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), private_include); it != std::sregex_iterator();
         ++it) {
      ++included;
      EXPECT_EQ(file.extension(), ".cpp") << fs::relative(file, kSource) << " includes " << it->str();
    }
  }
  EXPECT_GE(included, 3); // CGAL's surface mesh: surface_check, surface_remesh, mesh_boolean
}

TEST(Architecture, NothingCitesFilesOutsideTheRepository)
{
  int files = 0;
  for (auto it = fs::recursive_directory_iterator(kSource); it != fs::recursive_directory_iterator(); ++it) {
    const std::string name = it->path().filename().string();
    if (it->is_directory() && (name.starts_with(".") || name == "build" || name == "out")) {
      it.disable_recursion_pending();
      continue;
    }
    const std::string ext = it->path().extension().string();
    if (!it->is_regular_file() ||
        !(ext == ".cpp" || ext == ".hpp" || ext == ".md" || ext == ".txt" || ext == ".cmake" || ext == ".toml"))
      continue;
    ++files;
    const std::string text = text_of(it->path());
    // Spelt in pieces, so that this file does not cite them itself.
    for (const std::string& outside : {std::string("DESIGN") + ".md", std::string("STYLE") + ".md",
                                       std::string("../") + "shared", std::string("DEPENDENCIES") + ".md"})
      EXPECT_EQ(text.find(outside), std::string::npos) << fs::relative(it->path(), kSource) << " cites " << outside;
  }
  EXPECT_GT(files, 200);
}

/// What a shell command prints on its standard output.
std::string output_of(const std::string& command)
{
  std::string out;
  if (FILE* p = popen(command.c_str(), "r")) {
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, p)) > 0;) out.append(buffer, n);
    pclose(p);
  }
  return out;
}

/// Every .cpp and .hpp the project holds: the module folders, tests/ and bench/.
std::vector<fs::path> all_sources()
{
  std::vector<fs::path> out = module_sources();
  for (const char* folder : {"tests", "bench"}) add_sources(kSource / folder, out);
  std::sort(out.begin(), out.end());
  return out;
}

/// Formatting is kept by the tool: every source file is as .clang-format has it
/// (`clang-format -i FILE` fixes one). scripts/setup installs clang-format.
TEST(Architecture, EverySourceFileIsAsClangFormatHasIt)
{
  ASSERT_EQ(std::system("command -v clang-format > /dev/null 2>&1"), 0) << "clang-format is missing: run scripts/setup";
  std::string command = "cd '" + kSource.string() + "' && clang-format --dry-run -Werror";
  for (const fs::path& p : all_sources()) command += " '" + fs::relative(p, kSource).string() + "'";
  const std::string out = output_of(command + " 2>&1");
  EXPECT_TRUE(out.empty()) << "files .clang-format would reformat (run clang-format -i on them):\n" << out;
}

/// No line is longer than .clang-format's ColumnLimit, 120 characters (UTF-8 code points, as
/// clang-format counts them), raw strings (embedded script, regular expressions) included.
TEST(Architecture, NoLineIsLongerThan120Columns)
{
  constexpr std::size_t kColumns = 120;
  std::string over;
  for (const fs::path& p : all_sources()) {
    std::istringstream in(text_of(p));
    int number = 0;
    for (std::string line; std::getline(in, line);) {
      ++number;
      const auto columns = static_cast<std::size_t>(std::count_if(
          line.begin(), line.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
      if (columns > kColumns)
        over += fmt::format("{}:{}: {} columns\n", fs::relative(p, kSource).string(), number, columns);
    }
  }
  EXPECT_TRUE(over.empty()) << over;
}

/// SI inside; a figure goes to mm, mm², mm³, mL, g or degrees at the edges through core/units.hpp's
/// names (`length / units::mm`), never a bare factor: `/ 1e-3` reads as millimetres only to whoever
/// wrote it, and `* 1e3` is as likely kilopascals or grams (session 44 found 70 such, the STL check
/// and the STL writer scaling by different factors).
TEST(Architecture, UnitsAreConvertedThroughCoreUnits)
{
  const std::regex bare(R"((/\s*1e-(3|6|9)\b)|(\*\s*1e3\b)|(M_PI\s*/\s*180)|(180(\.0)?\s*/\s*M_PI))");
  std::string found;
  for (const fs::path& p : module_sources()) {
    if (fs::relative(p, kSource) == fs::path("core/units.hpp")) continue;
    std::istringstream in(text_of(p));
    int number = 0;
    for (std::string line; std::getline(in, line);) {
      ++number;
      if (std::regex_search(line, bare))
        found += fmt::format("{}:{}: {}\n", fs::relative(p, kSource).string(), number, line);
    }
  }
  EXPECT_TRUE(found.empty()) << "convert with core/units.hpp's names (units::mm, mm2, mm3, mL, gram, kPa, degree):\n"
                             << found;
}

} // namespace
} // namespace fibermold

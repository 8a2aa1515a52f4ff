#include "test_support.hpp"

#include "primitives.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

#include <sys/wait.h>
#include <unistd.h>

namespace fibermold::test {

namespace fs = std::filesystem;

TempDir::TempDir()
{
  std::string pattern = (fs::temp_directory_path() / "fibermold-test-XXXXXX").string();
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
  path_ = pattern;
}

TempDir::~TempDir()
{
  std::error_code ec;
  fs::remove_all(path_, ec);
}

void write_text(const fs::path& path, const std::string& text)
{
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string read_text(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

CommandResult run_fibermold(const std::string& arguments, const fs::path& cwd, const std::string& launcher)
{
  TempDir capture;
  const fs::path out = capture / "stdout", err = capture / "stderr";
  std::string command;
  if (!cwd.empty()) command += "cd '" + cwd.string() + "' && ";
  command += launcher + " '" FIBERMOLD_BINARY "' " + arguments + " </dev/null >'" + out.string() + "' 2>'" +
             err.string() + "'";
  const int status = std::system(command.c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.out = read_text(out);
  result.err = read_text(err);
  return result;
}

void write_bar(const fs::path& dir)
{
  write_ascii_stl(dir / "bar.stl", box({0, -0.008, -0.008}, {0.06, 0.008, 0.008}, Eigen::Vector3i(10, 3, 3)));
}

std::pair<int, std::string> run_command(const std::string& command)
{
  std::string text;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return {-1, text};
  char buffer[4096];
  while (fgets(buffer, sizeof buffer, pipe)) text += buffer;
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
}

std::map<std::string, int> admesh(const fs::path& stl)
{
  std::map<std::string, int> counts;
  const std::regex entry(R"(^\s*([A-Za-z ]+?)\s*:\s*(-?\d+)(\s|$))"); // "Number of parts : 1   Volume : ..."
  std::istringstream lines(run_command("admesh '" + stl.string() + "'").second);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_search(line, m, entry)) counts[m[1]] = std::stoi(m[2]);
  }
  return counts;
}

BrowserView open_in_browser(const fs::path& page, const fs::path& screenshot)
{
  const std::string browser =
      "chromium --headless=new --no-sandbox --enable-unsafe-swiftshader --use-angle=swiftshader "
      "--virtual-time-budget=4000 --enable-logging=stderr --v=0 ";
  const std::string url = "'file://" + fs::absolute(page).string() + "'";
  auto [code, dom] = run_command(browser + "--dump-dom " + url);
  if (code == 0 && !screenshot.empty())
    code = run_command(browser + "--window-size=1000,800 --screenshot='" + screenshot.string() + "' " + url).first;
  return {code, dom};
}

std::vector<std::string> blas_kernels()
{
  if (!std::filesystem::exists("/proc/cpuinfo")) return {};
  std::set<std::string> flags;
  std::istringstream lines(read_text("/proc/cpuinfo"));
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("flags", 0) == 0) {
      std::istringstream words(line.substr(line.find(':') + 1));
      for (std::string word; words >> word;) flags.insert(word);
      break;
    }
  if (!flags.contains("avx2")) return {};
  std::vector<std::string> kernels{"Haswell", "Sandybridge"};
  if (flags.contains("avx512f") && flags.contains("avx512bw") && flags.contains("avx512vl"))
    kernels.push_back("SkylakeX");
  // Each as OpenBLAS says it took it (an OpenBLAS built without DYNAMIC_ARCH ignores OPENBLAS_CORETYPE, and a test
  // that compares its kernels would compare one with itself).
  std::erase_if(kernels, [](const std::string& kernel) {
    const CommandResult r = run_fibermold("--version", {}, "env OPENBLAS_VERBOSE=2 OPENBLAS_CORETYPE=" + kernel);
    return (r.out + r.err).find("Core: " + kernel) == std::string::npos;
  });
  return kernels.size() >= 2 ? kernels : std::vector<std::string>{};
}

} // namespace fibermold::test

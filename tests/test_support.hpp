#pragma once
// Helpers shared by the test suites: temporary folders, files, running the fibermold binary.

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace fibermold::test {

/// A fresh folder under the system's temp dir, removed with its content at destruction.
class TempDir {
public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
  std::filesystem::path path_;
};

void write_text(const std::filesystem::path& path, const std::string& text);
std::string read_text(const std::filesystem::path& path);

/// Result of running a command: exit code and what it printed.
struct CommandResult {
  int exit_code = -1;
  std::string out; ///< stdout
  std::string err; ///< stderr
};

/// Runs the fibermold binary under test with `arguments` (a shell-quoted string), in `cwd`, under
/// `launcher` when given (e.g. "timeout -s INT 5").
CommandResult run_fibermold(const std::string& arguments, const std::filesystem::path& cwd = {},
                            const std::string& launcher = {});

/// The OpenBLAS kernels this CPU can run, to be chosen in a test's own environment
/// (`env OPENBLAS_CORETYPE=<kernel>`): each rounds dgemm and dpotrf its own way, as other machines
/// do. Haswell (AVX2) and Sandybridge (AVX) where the CPU has AVX2, and SkylakeX where it has
/// AVX-512 (what OpenBLAS picks itself on the AMD EPYC this suite was written on), each kept only
/// where fibermold's OpenBLAS says it took it (OPENBLAS_VERBOSE=2: "Core: Haswell"); empty when
/// fewer than two are left (no AVX2, no /proc/cpuinfo, an OpenBLAS that ignores the choice).
std::vector<std::string> blas_kernels();

/// The bar of the end-to-end tests: 60 × 16 × 16 mm from x = 0, written as `bar.stl` into `dir`.
void write_bar(const std::filesystem::path& dir);
// Its design file in pieces (TOML), constants so that tests may build theirs at namespace scope:
// the opening ([design] "bar" on bar.stl, [mesh] at 8 mm, [[fixed]] at x = 0), a wavy muscle m1
// end to end, the straight tracking curve "centre" along the axis, and the target "s" (m1 bent into
// another wave at 300 kPa, a known solution).
inline constexpr const char* kBarDesign = R"([design]
name = "bar"
surface = "bar.stl"
[mesh]
edge_length = 8
[[fixed]]
box = { min = [-1, -9, -9], max = [0.5, 9, 9] }
)";

inline constexpr const char* kBarMuscle = R"([[fiber]]
name = "m1"
points = [[0, 0, 0], [20, 3, -3], [40, -3, 2], [60, 0, 0]]
)";

inline constexpr const char* kBarTrackingCurve = R"([[tracking_curve]]
name = "centre"
points = [[0, 0, 0], [60, 0, 0]]
samples = 20
)";

inline constexpr const char* kBarTarget = R"([[target]]
name = "s"
kind = "fibers"
fibers = [{ name = "m1", pressure = 300, points = [[0, 0, 0], [20, 0, 3], [40, 0, -3], [60, 0, 0]] }]
)";

/// Runs a shell command: its exit status and what it printed (stdout and stderr together).
std::pair<int, std::string> run_command(const std::string& command);

/// admesh's verdict on an STL: the counts it prints ("Degenerate facets", "Edges fixed",
/// "Facets removed", "Backwards edges", "Number of parts", ...); empty when it did not run.
std::map<std::string, int> admesh(const std::filesystem::path& stl);

/// A report page opened in headless Chromium (software WebGL): the page's DOM once its scripts
/// have run, or the browser's output when it failed. Empty `screenshot`: no screenshot.
struct BrowserView {
  int exit_code = -1;
  std::string dom;
};
BrowserView open_in_browser(const std::filesystem::path& page, const std::filesystem::path& screenshot = {});

} // namespace fibermold::test

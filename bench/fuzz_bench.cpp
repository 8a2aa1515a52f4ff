// Fuzzing at scale: thousands of design-file and mesh mutants (tests/mutants.hpp) through
// `fibermold check`, and those check passes through `make`, each held to the rules of
// tests/fuzz.hpp (exit codes 0, 1, 2 only; no signal, no hang; no NaN or null in any JSON output;
// check passes ⇒ make does not exit 2). The suite runs a few hundred (tests/e2e/fuzz_test.cpp).
// Run: build/bench/fuzz_bench [design mutants = 3000] [mesh mutants = 400] [makes = 60] [seed = 1]

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <unistd.h>

#include "core/atomic_file.hpp"
#include "export/stl_writer.hpp"
#include "fuzz.hpp"
#include "mutants.hpp"
#include "primitives.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace fibermold;

namespace {

// The suite's bar (tests/test_support.hpp) with a quick optimizer and coarse molds, as in tests/e2e/fuzz_test.cpp.
const std::string kDesign = std::string(test::kBarDesign) + test::kBarMuscle + test::kBarTrackingCurve +
                            test::kBarTarget +
                            "[optimize]\nmax_iterations = 2\n[mold]\nvoxel = 0.6\nwall = 3\nkeys = 2\n";

struct Tally {
  int runs = 0, makes = 0, crashes = 0, hangs = 0, violations = 0;
  std::map<int, int> check, make;
  std::vector<std::string> first;
};

void run(const std::vector<test::Mutant>& mutants, bool mesh, const std::string& bar_stl, int& makes_left, Tally& t)
{
  const fs::path dir = fs::temp_directory_path() / ("fibermold-fuzz-" + std::to_string(::getpid()));
  for (const test::Mutant& m : mutants) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    write_file_atomic(dir / "design.toml", mesh ? kDesign : m.text);
    write_file_atomic(dir / "bar.stl", mesh ? m.text : bar_stl);
    const test::FuzzRun r = test::fuzz_run(dir, makes_left > 0, 30, 300);
    ++t.runs;
    ++t.check[r.check];
    if (r.make >= 0) ++t.make[r.make], ++t.makes, --makes_left;
    if (!r.problem.empty()) {
      ++t.violations;
      if (r.problem.find("hung") != std::string::npos) ++t.hangs;
      if (r.problem.find("signal") != std::string::npos) ++t.crashes;
      if (t.first.size() < 10) t.first.push_back(m.what + " → " + r.problem);
    }
    if (t.runs % 200 == 0) std::fprintf(stderr, "  %d runs, %d makes, %d violations\n", t.runs, t.makes, t.violations);
  }
  fs::remove_all(dir);
}

void print(const char* name, const Tally& t)
{
  std::printf("%-16s %6d runs  check: ", name, t.runs);
  for (const auto& [code, n] : t.check) std::printf("exit %d ×%d  ", code, n);
  std::printf("| %d makes: ", t.makes);
  for (const auto& [code, n] : t.make) std::printf("exit %d ×%d  ", code, n);
  std::printf("| crashes %d, hangs %d, rules broken %d\n", t.crashes, t.hangs, t.violations);
  for (const std::string& f : t.first) std::printf("    %s\n", f.c_str());
}

} // namespace

int main(int argc, char** argv)
{
  const int designs = argc > 1 ? std::atoi(argv[1]) : 3000, meshes = argc > 2 ? std::atoi(argv[2]) : 400;
  int makes = argc > 3 ? std::atoi(argv[3]) : 60;
  const std::uint64_t seed = argc > 4 ? std::strtoull(argv[4], nullptr, 10) : 1;
  const fs::path scratch = fs::temp_directory_path() / ("fibermold-fuzz-bar-" + std::to_string(::getpid()) + ".stl");
  write_stl(scratch, test::box({0, -0.008, -0.008}, {0.06, 0.008, 0.008}, Eigen::Vector3i(10, 3, 3)));
  const std::string bar = read_file(scratch);
  fs::remove(scratch);

  const auto started = std::chrono::steady_clock::now();
  Tally design_tally, mesh_tally;
  int design_makes = makes * 5 / 6, mesh_makes = makes - design_makes;
  run(test::design_mutants(kDesign, designs, seed), false, bar, design_makes, design_tally);
  run(test::mesh_mutants(bar, meshes, seed), true, bar, mesh_makes, mesh_tally);
  std::printf("fuzz_bench (seed %llu), %.0f s\n", static_cast<unsigned long long>(seed),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  print("design mutants", design_tally);
  print("mesh mutants", mesh_tally);
  return design_tally.violations + mesh_tally.violations == 0 ? 0 : 1;
}

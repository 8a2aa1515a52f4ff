// Time and peak memory of the molds and export stages for the walking robot's body (42 × 20 × 14 mm
// on four legs) with its three hand-routed fibers, at voxel 0.2 mm and 0.1 mm (or the voxels given).
// The body is meshed and the fibers are moved apart first (not timed); molds + export then run in
// a child process of their own, so that its peak resident memory is theirs. Goal: ≤ 10 s at 0.1 mm on 2 cores.
//   build/bench/molds_bench [--draft DEG] [VOXEL_MM ...]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "design/design_file.hpp"
#include "make/runner.hpp"
#include "stages/stages.hpp"

using namespace fibermold;
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

/// The walking robot with its [[fiber]] routes as they are: no targets, no optimization.
Design hand_routed_walking_robot(double voxel_mm, double draft_deg)
{
  Design d = load_design(fs::path(FIBERMOLD_SOURCE_DIR) / "examples" / "walking-robot" / "design.toml");
  d.targets.clear();
  d.optimize.enabled = false;
  d.collide.reoptimize = false;
  d.mold.voxel = voxel_mm * 1e-3;
  d.mold.draft_deg = draft_deg;
  return d;
}

/// Seconds a stage took, from its log's last line ("done in 12.34 s").
double stage_seconds(const fs::path& build, const std::string& stage)
{
  const std::string log = read_file(build / "logs" / (stage + ".log"));
  const auto at = log.rfind("done in ");
  return at == std::string::npos ? NAN : std::stod(log.substr(at + 8));
}

void run(double voxel_mm, double draft_deg)
{
  const Design d = hand_routed_walking_robot(voxel_mm, draft_deg);
  const fs::path build = fs::temp_directory_path() / "fibermold-bench-molds";
  fs::remove_all(build);
  const Runner runner(shipped_stages());
  // Each step in a child of its own: this process never starts oneTBB's threads, which a forked
  // child would not have.
  const auto in_child = [&](const std::string& stage, rusage& usage) {
    const pid_t child = fork();
    if (child == 0) {
      try {
        runner.make(d, {build, {stage}, false});
        _exit(0);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "%s failed: %s\n", stage.c_str(), e.what());
        _exit(1);
      }
    }
    int status = 0;
    wait4(child, &status, 0, &usage);
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
  };
  rusage usage{};
  if (!in_child("collide", usage)) {
    std::printf("| %.2f | mesh or collide failed (see %s/logs) |\n", voxel_mm, build.c_str());
    return;
  }
  const auto started = Clock::now();
  const bool ok = in_child("export", usage);
  const double wall = std::chrono::duration<double>(Clock::now() - started).count();
  if (!ok) {
    std::printf("| %.2f | failed (see %s/logs) |\n", voxel_mm, build.c_str());
    return;
  }
  const auto report = nlohmann::json::parse(read_file(build / "molds" / "report.json"));
  long triangles = 0;
  std::string per_part;
  for (const auto& [name, p] : report["parts"].items()) {
    triangles += p["triangles"].get<long>();
    per_part += (per_part.empty() ? "" : ", ") + name + " " + std::to_string(p["triangles"].get<long>() / 1000) + "k";
  }
  std::printf("| %.2f | %.1f | %.1f | %.1f | %.0f | %ldk (%s) | %.2f + %.2f |\n", voxel_mm,
              stage_seconds(build, "molds"), stage_seconds(build, "export"), wall, usage.ru_maxrss / 1024.0,
              triangles / 1000, per_part.c_str(), report["shots"]["shot1"]["silicone_volume_mL"].get<double>(),
              report["shots"]["shot2"]["silicone_volume_mL"].get<double>());
  std::fflush(stdout);
}

} // namespace

int main(int argc, char** argv)
{
  std::vector<double> voxels;
  double draft_deg = 0;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--draft" && i + 1 < argc)
      draft_deg = std::stod(argv[++i]);
    else
      voxels.push_back(std::stod(argv[i]));
  }
  if (voxels.empty()) voxels = {0.2, 0.1};
  if (draft_deg > 0) std::printf("draft %.1f°\n", draft_deg);
  std::printf("| voxel mm | molds s | export s | wall s | peak MiB | triangles | silicone mL (shot 1 + 2) "
              "|\n|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  for (double v : voxels) run(v, draft_deg);
}

// Optimization speed and accuracy on the paper's examples: recovery (section VIII-B), the
// twisting bar (VIII-C; Table II: 381 iterations, 169 min on a 4-core i7; surface RMSE 1.9 mm, max
// 4.8 mm) and the walking robot (VIII-F; Table II: bend 18 iterations, 76 min; twist 31, 85 min,
// optimized separately). Runs the pipeline up to optimize (walking robot: up to collide) in a
// temporary folder and prints a Markdown table with the time per iteration split into simulation,
// adjoint and the rest (line search, regularizers), the first target's errors, and for the
// walking robot every target's errors before and after collide moved the fibers apart.
//   build/bench/optimize_bench [recovery|twisting-bar|walking-robot ...]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "core/array_file.hpp"
#include "core/atomic_file.hpp"
#include "core/units.hpp"
#include "design/design_file.hpp"
#include "make/runner.hpp"
#include "stages/design_simulation.hpp"
#include "stages/fibers_file.hpp"
#include "stages/stages.hpp"

using namespace fibermold;
namespace fs = std::filesystem;

namespace {

struct Paper {
  double minutes, iterations, rmse, max;
};

/// Mean rotation (degrees) about +x of the body's end face at x = max: each surface node's (y, z)
/// offset from the face's centroid, rest against deformed.
double end_twist_deg(const TetMesh& mesh, const Eigen::MatrixX3d& deformed)
{
  const double end = mesh.nodes.col(0).maxCoeff();
  std::vector<int> face;
  for (Eigen::Index i = 0; i < mesh.nodes.rows(); ++i)
    if (mesh.nodes(i, 0) > end - 1e-4) face.push_back(static_cast<int>(i));
  Eigen::Vector2d c0 = Eigen::Vector2d::Zero(), c = Eigen::Vector2d::Zero();
  for (int i : face) {
    c0 += mesh.nodes.row(i).tail<2>().transpose() / face.size();
    c += deformed.row(i).tail<2>().transpose() / face.size();
  }
  double sum = 0, weight = 0;
  for (int i : face) {
    const Eigen::Vector2d r0 = mesh.nodes.row(i).tail<2>().transpose() - c0,
                          r = deformed.row(i).tail<2>().transpose() - c;
    if (r0.norm() < 1e-3) continue;
    sum += r0.norm() * std::atan2(r0.x() * r.y() - r0.y() * r.x(), r0.dot(r));
    weight += r0.norm();
  }
  return sum / weight * 180 / M_PI;
}

/// The twist of the target and of the optimized design for the twisting bar's only target.
void twist_angles(const Design& d, const fs::path& build, double& target_deg, double& reached_deg)
{
  const TetMesh mesh = load_tet_mesh(build / "mesh" / "body.tetmesh");
  Simulation sim(mesh, simulation_options(d, mesh));
  const Eigen::VectorXd target = load_array(build / "targets" / (d.targets[0].name + ".positions"), "positions");
  target_deg = end_twist_deg(mesh, sim.deformed_nodes(target));
  const FibersFile fibers = read_fibers_json(build / "optimize" / "fibers.json");
  std::vector<Actuation> actuations;
  for (std::size_t f = 0; f < fibers.routing.routes.size(); ++f) {
    const Route& r = fibers.routing.routes[f];
    actuations.push_back({r.name, r.points, r.tangents, fibers.routing.pressures(0, static_cast<Eigen::Index>(f))});
  }
  const MuscleModel model(d.muscle.model); // the muscles keep a reference to it
  add_muscles(sim, d, model, actuations);
  Eigen::VectorXd x = sim.rest();
  NullProgress progress;
  const NewtonSummary s = sim.solve(x, progress);
  // From rest (the optimizer warm-starts); an unconverged state would report a meaningless angle.
  reached_deg = s.converged ? end_twist_deg(mesh, sim.deformed_nodes(x)) : NAN;
  if (!s.converged)
    std::fprintf(stderr, "re-simulating the optimized design from rest: %s (%s)\n", s.brief().c_str(),
                 s.message.c_str());
}

void run(const std::string& example, const Paper& paper)
{
  const Design d = load_design(fs::path(FIBERMOLD_SOURCE_DIR) / "examples" / example / "design.toml");
  const fs::path build = fs::temp_directory_path() / ("fibermold-bench-" + example);
  fs::remove_all(build);
  Runner runner(shipped_stages());
  const bool collide = example == "walking-robot";
  runner.make(d, {build, {collide ? "collide" : "optimize"}, false}, nullptr);
  const auto report = nlohmann::json::parse(read_file(build / "optimize" / "report.json"));
  const auto mesh_report = nlohmann::json::parse(read_file(build / "mesh" / "report.json"));
  const auto& t = report["targets"].begin().value();
  const int it = report["iterations"].get<int>();
  const double total = report["seconds"]["total"], simulation = report["seconds"]["simulation"],
               adjoint = report["seconds"]["adjoint"];
  const std::string speedup =
      paper.minutes > 0 ? std::to_string(static_cast<int>(paper.minutes / (total / 60))) + "×" : "—";
  std::printf("| %s | %s | %s | %d | %.1f | %s | %.2f | %.2f | %.2f | %.3f / %.3f | %.3f / %.3f | %.2f / %.2f |\n",
              example.c_str(), mesh_report["mesh"]["tets"].dump().c_str(), mesh_report["mesh"]["nodes"].dump().c_str(),
              it, total / 60, speedup.c_str(), simulation / it, adjoint / it, (total - simulation - adjoint) / it,
              t["rmse_mm"].get<double>(), t["max_error_mm"].get<double>(), t["surface_rmse_mm"].get<double>(),
              t["surface_max_error_mm"].get<double>(), paper.rmse, paper.max);
  if (example == "twisting-bar") {
    double target_deg = 0, reached_deg = 0;
    twist_angles(d, build, target_deg, reached_deg);
    std::printf("|   twist of the free end: target %.1f°, reached %.1f° (paper: 39.3°) |\n", target_deg, reached_deg);
  }
  if (collide) {
    const auto c = nlohmann::json::parse(read_file(build / "collide" / "report.json"));
    std::printf("|   collide: %zu colliding pair(s), smallest clearance %s → %s mm |\n", c["collisions"].size(),
                c["smallest_clearance_mm"]["before"].dump().c_str(),
                c["smallest_clearance_mm"]["after"].dump().c_str());
    for (const auto& [name, e] : c["targets"].items())
      std::printf("|   %s: curve RMSE %.3f → %.3f mm (%+.1f %%), surface RMSE %.3f → %.3f mm |\n", name.c_str(),
                  e["before"]["rmse_mm"].get<double>(), e["after"]["rmse_mm"].get<double>(),
                  e["rmse_change_percent"].get<double>(), e["before"]["surface_rmse_mm"].get<double>(),
                  e["after"]["surface_rmse_mm"].get<double>());
  }
  std::fflush(stdout);
}

} // namespace

int main(int argc, char** argv)
{
  std::vector<std::string> examples(argv + 1, argv + argc);
  if (examples.empty()) examples = {"recovery", "twisting-bar"};
  std::printf("| example | tets | nodes | iterations | minutes | vs paper | sim s/it | adjoint s/it | rest s/it | "
              "curve RMSE / max mm | surface RMSE / max mm | paper RMSE / max mm "
              "|\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& e : examples) {
    if (e == "recovery")
      run(e, {0, 0, 0.10, 0.20});
    else if (e == "twisting-bar")
      run(e, {169, 381, 1.9, 4.8});
    else if (e == "walking-robot")
      run(e, {76 + 85, 18 + 31, NAN, NAN});
    else
      std::fprintf(stderr, "unknown example %s\n", e.c_str());
  }
}

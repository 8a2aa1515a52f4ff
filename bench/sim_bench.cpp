// Forward simulation speed: the twisting bar on three meshes (paper Table II: 63 s on a 4-core i7) and the
// cantilever at three mesh sizes. Prints a Markdown table.
//   build/bench/sim_bench [--verbose] [--only example|tets|fine|cantilever]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "mesh/surface_import.hpp"
#include "mesh/tetrahedralize.hpp"
#include "primitives.hpp"
#include "sim/external_forces.hpp"
#include "sim/muscle_energy.hpp"
#include "sim/sim_fixtures.hpp"
#include "sim/simulation.hpp"

using namespace fibermold;

namespace {

struct Row {
  std::string name;
  Eigen::Index tets, nodes;
  NewtonSummary s;
  double setup;
};

void print(const Row& r, double paper_seconds)
{
  const double per_assembly = r.s.seconds_assembly / std::max(1, r.s.assemblies);
  const double per_factor = r.s.seconds_factorization / std::max(1, r.s.factorizations);
  std::printf("| %s | %ld | %ld | %d | %d | %.3f | %.3f | %.4f | %.3f | %.3f | %s |\n", r.name.c_str(),
              static_cast<long>(r.tets), static_cast<long>(3 * r.nodes), r.s.iterations, r.s.factorizations,
              per_assembly, per_factor, r.s.seconds_solve / std::max(1, r.s.iterations), r.setup, r.s.seconds_total,
              paper_seconds > 0 ? (std::to_string(static_cast<int>(paper_seconds / r.s.seconds_total)) + "×").c_str()
                                : "");
}

double since(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// --verbose: each Newton iteration of the twisting bar on stderr.
struct NewtonLog final : Progress {
  bool on = false;
  void update(double, std::string_view what) override
  {
    if (on) std::fprintf(stderr, "%.*s\n", static_cast<int>(what.size()), what.data());
  }
};

enum class BarMesh {
  example, ///< the example's bar.stl, 10 mm edges: 843 DoFs (the paper had 702)
  tets,    ///< about the paper's (and issue #5's) 2,400 tets: the 4.3 mm skin, 8 mm edges
  fine,    ///< 4× the example's DoFs (test::fine_twisting_bar: the 4.3 mm skin, 6 mm edges)
};

Row twisting_bar(BarMesh which, bool verbose)
{
  NewtonLog progress;
  progress.on = verbose;
  const TetMesh mesh = which == BarMesh::fine ? test::fine_twisting_bar()
                       : which == BarMesh::tets
                           ? test::skin_grid_twisting_bar(0.008)
                           : tetrahedralize(import_surface(FIBERMOLD_SOURCE_DIR "/examples/twisting-bar/bar.stl", 1e-3),
                                            {0.010, 1.5, 10, false}, progress);
  const auto start = std::chrono::steady_clock::now();
  SimulationOptions o;
  o.gravity = {9.81, 0, 0};
  o.fixed_nodes = {nodes_in_box(mesh.nodes, {-1, -1, -1}, {1e-9, 1, 1})};
  Simulation sim(mesh, o);
  const std::vector<Eigen::Vector3d> points = test::helix_points(0.129, 0.005, 1.5, +1);
  static const MuscleModel model;
  const HermiteSpline helix(points);
  sim.add_energy(std::make_unique<MuscleEnergy>(
      sim.basis(), model, helix, segment_parameters(helix, static_cast<int>(std::ceil(helix.length() * 500))), 300e3));
  Eigen::VectorXd x = sim.rest();
  const double setup = since(start);
  const char* name = which == BarMesh::fine   ? "twisting bar at 4x the DoFs, MLS-linear, helix at 300 kPa"
                     : which == BarMesh::tets ? "twisting bar at the paper's tet count, MLS-linear, helix at 300 kPa"
                                              : "twisting bar, MLS-linear, helix at 300 kPa";
  return {name, mesh.num_tets(), mesh.nodes.rows(), sim.solve(x, progress), setup};
}

Row cantilever(const std::string& basis, double edge)
{
  NullProgress progress;
  const Eigen::Vector3d size(0.1, 0.015, 0.015);
  const SurfaceMesh surface = test::box({0, -0.0075, -0.0075}, {0.1, 0.0075, 0.0075},
                                        (size / edge).array().round().cast<int>().max(1).matrix());
  const TetMesh mesh = tetrahedralize(surface, {edge, 1.5, 10, basis == "fem-p2"}, progress);
  const auto start = std::chrono::steady_clock::now();
  SimulationOptions o;
  o.basis = *value_in(kBasisNames, basis);
  o.fixed_nodes = {nodes_in_box(mesh.nodes, {-1, -1, -1}, {1e-9, 1, 1})};
  Simulation sim(mesh, o);
  Eigen::VectorXd x = sim.rest();
  const double setup = since(start);
  char name[96];
  std::snprintf(name, sizeof name, "cantilever, %s, %.0f mm edges, gravity", basis.c_str(), edge * 1e3);
  return {name, mesh.num_tets(), mesh.nodes.rows(), sim.solve(x, progress), setup};
}

} // namespace

int main(int argc, char** argv)
{
  bool verbose = false;
  std::string only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--verbose")
      verbose = true;
    else if (a == "--only" && i + 1 < argc)
      only = argv[++i];
    else {
      std::fprintf(stderr, "usage: %s [--verbose] [--only example|tets|fine|cantilever]\n", argv[0]);
      return 2;
    }
  }
  const auto runs = [&](const char* row) { return only.empty() || only == row; };
  std::printf("| case | tets | DoFs | Newton it. | factorizations | s/assembly | s/factorization | s/solve | setup s | "
              "total s | vs paper |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  if (runs("example")) print(twisting_bar(BarMesh::example, verbose), 63.0);
  if (runs("tets")) print(twisting_bar(BarMesh::tets, verbose && !only.empty()), 63.0);
  if (runs("fine")) print(twisting_bar(BarMesh::fine, verbose && !only.empty()), 63.0);
  if (!runs("cantilever")) return 0;
  for (double edge : {0.006, 0.004, 0.003}) print(cantilever("mls-linear", edge), 0);
  print(cantilever("fem-p2", 0.004), 0);
  return 0;
}

// The elastic energy's kernels on the twisting bar (≈3,900 tets, linear MLS, 8 points per tet), the
// inner loop of every Newton step: Hessian assembly (with the PSD projection), one-pass value and
// gradient, and CHOLMOD's factorization of the Hessian, at a twisted state.   build/bench/assembly_bench
// [--benchmark_repetitions=5]
#include <benchmark/benchmark.h>

#include "mesh/mesh_quality.hpp"
#include "sim/cholmod_solver.hpp"
#include "sim/mls_basis.hpp"
#include "sim/neo_hookean.hpp"
#include "sim/sim_fixtures.hpp"
#include "sim/sparse_hessian.hpp"

namespace fibermold {
namespace {

struct Bar {
  TetMesh mesh;
  std::unique_ptr<MlsBasis> basis;
  QuadraturePoints qp;
  std::unique_ptr<NeoHookean> energy;
  std::unique_ptr<SparseHessian> H;
  Eigen::VectorXd x;

  Bar()
  {
    mesh = test::fine_twisting_bar();
    basis = std::make_unique<MlsBasis>(mesh.nodes, MlsOptions{false, 1.7 * mesh_quality(mesh).mean_edge_length});
    qp = build_quadrature_points(mesh, *basis, 8);
    energy = std::make_unique<NeoHookean>(qp, mesh.nodes.rows(), LameParameters::from_young_poisson(86.4e3, 0.47));
    std::vector<std::vector<int>> stencils;
    energy->stencils(stencils);
    H = std::make_unique<SparseHessian>(mesh.nodes.rows(), stencils);
    // 20° of twist per 100 mm about the bar's long axis x.
    x.resize(3 * mesh.nodes.rows());
    for (Eigen::Index i = 0; i < mesh.nodes.rows(); ++i) {
      const Eigen::Vector3d X = mesh.nodes.row(i).transpose();
      const double angle = 3.49 * X.x();
      x.segment<3>(3 * i) = Eigen::Vector3d(X.x(), std::cos(angle) * X.y() - std::sin(angle) * X.z(),
                                            std::sin(angle) * X.y() + std::cos(angle) * X.z());
    }
  }
};

Bar& bar()
{
  static Bar b;
  return b;
}

void ElasticHessian(benchmark::State& state)
{
  Bar& b = bar();
  for (auto _ : state) {
    b.H->set_zero();
    b.energy->add_hessian(b.x, *b.H, state.range(0) != 0);
    benchmark::DoNotOptimize(b.H->matrix().valuePtr());
  }
  state.counters["quadrature_points"] = static_cast<double>(b.qp.size());
  state.counters["shape_function_entries"] = static_cast<double>(b.qp.node.size());
}
BENCHMARK(ElasticHessian)->ArgName("projected")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void ElasticValueAndGradient(benchmark::State& state)
{
  Bar& b = bar();
  Eigen::VectorXd g(b.x.size());
  for (auto _ : state) {
    g.setZero();
    benchmark::DoNotOptimize(b.energy->value_and_gradient(b.x, g));
  }
}
BENCHMARK(ElasticValueAndGradient)->Unit(benchmark::kMillisecond)->UseRealTime();

// CHOLMOD's numeric factorization of the projected Hessian (held by a small shift: the bar is free
// here), alone and right after an assembly, as Newton does it.
void Factorization(benchmark::State& state)
{
  Bar& b = bar();
  b.H->set_zero();
  b.energy->add_hessian(b.x, *b.H, true);
  const double shift = 1e-6 * b.H->matrix().diagonal().maxCoeff();
  CholmodSolver solver;
  solver.factorize(b.H->matrix(), shift);
  for (auto _ : state) {
    if (state.range(0)) {
      state.PauseTiming();
      b.H->set_zero();
      b.energy->add_hessian(b.x, *b.H, true);
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(solver.factorize(b.H->matrix(), shift));
  }
}
BENCHMARK(Factorization)->ArgName("after_assembly")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace
} // namespace fibermold

BENCHMARK_MAIN();

// Import, check and tetrahedralize: a ~100k-triangle surface and the bundled examples.
//   build/bench/mesh_bench [--benchmark_filter=...]
#include <filesystem>

#include <benchmark/benchmark.h>
#include <unistd.h>

#include "export/stl_writer.hpp"
#include "mesh/surface_check.hpp"
#include "mesh/surface_import.hpp"
#include "mesh/tetrahedralize.hpp"
#include "primitives.hpp"

namespace fibermold {
namespace {

namespace fs = std::filesystem;

/// A torus of 2 · 316 · 158 = 99,856 triangles, 120 mm across, written once as binary STL and
/// removed at exit.
const fs::path& big_surface()
{
  struct TempStl {
    fs::path path = fs::temp_directory_path() / ("fibermold-bench-torus-" + std::to_string(::getpid()) + ".stl");
    TempStl() { write_stl(path, test::torus(0.045, 0.015, 316, 158)); }
    ~TempStl() { fs::remove(path); }
  };
  static const TempStl file;
  return file.path;
}

const fs::path kBar = fs::path(FIBERMOLD_SOURCE_DIR) / "examples/twisting-bar/bar.stl";

void BM_Import(benchmark::State& state, const fs::path& path)
{
  for (auto _ : state) benchmark::DoNotOptimize(import_surface(path, 1e-3));
  state.counters["triangles"] = static_cast<double>(import_surface(path, 1e-3).num_faces());
}

void BM_Check(benchmark::State& state, const fs::path& path)
{
  const SurfaceMesh s = import_surface(path, 1e-3);
  for (auto _ : state) benchmark::DoNotOptimize(check_surface(s));
}

void BM_Tetrahedralize(benchmark::State& state, const fs::path& path, double edge)
{
  const SurfaceMesh s = import_surface(path, 1e-3);
  NullProgress progress;
  Eigen::Index tets = 0;
  for (auto _ : state) tets = tetrahedralize(s, {edge, 1.5, 10, false}, progress).num_tets();
  state.counters["tets"] = static_cast<double>(tets);
}

BENCHMARK_CAPTURE(BM_Import, torus_100k, big_surface())->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Check, torus_100k, big_surface())->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Tetrahedralize, torus_100k, big_surface(), 0.002)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Import, twisting_bar, kBar)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Check, twisting_bar, kBar)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Tetrahedralize, twisting_bar, kBar, 0.006)->Unit(benchmark::kMillisecond);

} // namespace
} // namespace fibermold

BENCHMARK_MAIN();

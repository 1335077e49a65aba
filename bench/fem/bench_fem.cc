// FEM reference speed: setup, assembly and solve time against DoFs for the 2D plate (plane stress,
// to 1e-8 relative residual), from 1.6e4 to 4e6 DoFs; iterations and peak memory per DoF.
// PlateQ1Mg / PlateQ2Mg: CG + matrix-free geometric multigrid (the default above direct_limit);
// PlateQ1 / PlateQ2: CG + ML AMG.
//   build-femperf/bench/fem/fem_bench --benchmark_filter=PlateQ1   (results: docs/performance.md)
// The 1 vs 2 MPI ranks comparison is bench/fem/mpi_ranks.sh.
#include <fem_reference/fem.h>

#include <benchmark/benchmark.h>

namespace {

/// The seed plate's geometry scaled to 88 x 88 coarse cells (W = H = 0.176 m, h = 2 mm, load patch
/// 16 mm), refined `refine` times: 2 * (88 * 2^r + 1)^2 DoFs.
fem_reference::FemProblem plate(int refine, int degree, fem_reference::SolverKind solver) {
  fem_reference::FemProblem p;
  p.name = "bench plate";
  p.mesh_file = WORKBENCH_SOURCE_DIR "/meshes/plate2d.geo";
  p.mesh_parameters = {{"W", 0.176}, {"H", 0.176}, {"h", 0.002}, {"lw", 0.016}};
  p.young = 206e9;
  p.poisson = 0.3;
  p.thickness = 0.002;
  p.supports.push_back({"base", fem_reference::SupportKind::Clamped, {}});
  p.tractions.push_back({"load", {0.0, -2.0, 0.0}, {}});
  p.options.degree = degree;
  p.options.refine = refine;
  p.options.solver = solver;
  p.options.tolerance = 1e-8;
  return p;
}

void run(benchmark::State& state, int degree, fem_reference::SolverKind solver) {
  const auto problem = plate(int(state.range(0)), degree, solver);
  fem_reference::FemResult r;
  for (auto _ : state) r = fem_reference::solve_fem(problem);
  state.counters["dofs"] = double(r.n_dofs);
  state.counters["setup_s"] = r.setup_seconds;
  state.counters["assemble_s"] = r.assemble_seconds;
  state.counters["solve_s"] = r.solve_seconds;
  state.counters["iterations"] = r.iterations;
  state.counters["residual"] = r.residual;
  state.counters["peak_bytes_per_dof"] = r.peak_memory_bytes / double(r.n_dofs);
}

void BM_PlateQ1(benchmark::State& state) { run(state, 1, fem_reference::SolverKind::Amg); }
void BM_PlateQ2(benchmark::State& state) { run(state, 2, fem_reference::SolverKind::Amg); }
void BM_PlateQ1Mg(benchmark::State& state) { run(state, 1, fem_reference::SolverKind::Mg); }
void BM_PlateQ2Mg(benchmark::State& state) { run(state, 2, fem_reference::SolverKind::Mg); }

}  // namespace

BENCHMARK(BM_PlateQ1)->DenseRange(0, 4)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_PlateQ2)->DenseRange(0, 3)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_PlateQ1Mg)->DenseRange(0, 4)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_PlateQ2Mg)->DenseRange(0, 3)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_MAIN();

// FEM reference speed: setup, assembly and solve time against DoFs for the 2D plate (plane stress,
// to 1e-8 relative residual), from 1.6e4 to 4e6 DoFs; iterations and peak memory per DoF.
// PlateQ1Mg / PlateQ2Mg: CG + matrix-free geometric multigrid (the default above direct_limit);
// PlateQ1 / PlateQ2: CG + ML AMG.
//   build-femperf/bench/fem/fem_bench --benchmark_filter=PlateQ1   (results: docs/performance.md)
// The 1 vs 2 MPI ranks comparison is bench/fem/mpi_ranks.sh.
// Sweep (--sweep=dim,degree,cells,refine,solver): one solver on a unit square/cube, the solver sweep
// of bench/fem/solver_sweep.py (is `auto` within 2x of the best solver everywhere?).
#include <fem_reference/fem.h>

#include <benchmark/benchmark.h>

#include <cstdio>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

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

/// Sweep/dim/degree/cells/refine/solver: a unit square (cube) of cells^dim elements refined `refine`
/// times, clamped at y = 0, 1 MN/m (N/m^2) downwards on y = 1, to 1e-8. solver: 0 auto, 1 direct,
/// 2 amg, 3 mg. cpu_s: CPU time of the whole solve_fem (setup, assembly, solve, postprocessing),
/// which is what the solvers differ in; the label names the solver that ran.
void BM_Sweep(benchmark::State& state) {
  const int dim = int(state.range(0));
  const int cells = int(state.range(2));
  fem_reference::FemProblem p;
  p.name = "sweep";
  fem_reference::Box box;
  box.cells = {cells, cells, dim == 3 ? cells : 0};
  p.box = box;
  p.supports.push_back({"y0", fem_reference::SupportKind::Clamped, {}});
  p.tractions.push_back({"y1", {0.0, -1e6, 0.0}, {}});
  p.options.degree = int(state.range(1));
  p.options.refine = int(state.range(3));
  const fem_reference::SolverKind kinds[] = {fem_reference::SolverKind::Auto, fem_reference::SolverKind::Direct,
                                             fem_reference::SolverKind::Amg, fem_reference::SolverKind::Mg};
  p.options.solver = kinds[state.range(4)];
  p.options.tolerance = 1e-8;
  fem_reference::FemResult r;
  double cpu = 0;
  for (auto _ : state) {
    const std::clock_t start = std::clock();
    r = fem_reference::solve_fem(p);
    cpu = double(std::clock() - start) / CLOCKS_PER_SEC;
  }
  state.SetLabel(r.solver);
  state.counters["dofs"] = double(r.n_dofs);
  state.counters["cpu_s"] = cpu;
  state.counters["solve_s"] = r.solve_seconds;
  state.counters["iterations"] = r.iterations;
  state.counters["peak_bytes_per_dof"] = r.peak_memory_bytes / double(r.n_dofs);
}

}  // namespace

BENCHMARK(BM_PlateQ1)->DenseRange(0, 4)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_PlateQ2)->DenseRange(0, 3)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_PlateQ1Mg)->DenseRange(0, 4)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_PlateQ2Mg)->DenseRange(0, 3)->Unit(benchmark::kSecond)->Iterations(1);

/// Standard Google Benchmark main, plus `--sweep=dim,degree,cells,refine,solver` (repeatable):
/// registers Sweep/<those five> (bench/fem/solver_sweep.py runs one per process).
int main(int argc, char** argv) {
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--sweep=", 0) != 0) {
      rest.push_back(argv[i]);
      continue;
    }
    std::vector<int64_t> a;
    std::stringstream in(arg.substr(8));
    for (std::string item; std::getline(in, item, ',');) a.push_back(std::stoll(item));
    if (a.size() != 5) {
      std::fprintf(stderr, "fem_bench: --sweep needs dim,degree,cells,refine,solver\n");
      return 2;
    }
    benchmark::RegisterBenchmark("Sweep", BM_Sweep)->Args(a)->Unit(benchmark::kSecond)->Iterations(1);
  }
  int n = int(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

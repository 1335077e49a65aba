// FEM reference speed: setup, assembly and solve time against DoFs for the 2D plate (plane stress,
// to 1e-8 relative residual), from 1.6e4 to 4e6 DoFs; iterations and peak memory per DoF.
// PlateQ1Mg / PlateQ2Mg: CG + matrix-free geometric multigrid (the default above direct_limit);
// PlateQ1 / PlateQ2: CG + ML AMG.
//   build-femperf/bench/fem/fem_bench --benchmark_filter=PlateQ1   (results: docs/performance.md)
// The 1 vs 2 MPI ranks comparison is bench/fem/mpi_ranks.sh.
// Sweep (--sweep=dim,degree,cells,refine,solver): one solver on a unit square/cube, the solver sweep
// of bench/fem/solver_sweep.py (is `auto` within 2x of the best solver everywhere?).
// BM_Small/case/degree/n/solver/runs, the ladder of issue 38 (Small/... with --small=case,degree,
// n,solver,runs): the seed plate (case 0) or block3d (1) at mesh size h = 8 mm / n, or the sweep's
// unit square (2) or cube (3) of n cells per side; min and median of `runs` warm solve_fem calls
// without the mesh (bench/fem/dolfinx_small.py runs DOLFINx beside it):
//   taskset -c 1 build/bench/fem/fem_bench --benchmark_filter=BM_Small
#include <fem_reference/fem.h>
#include <fem_reference/fem_case.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
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
fem_reference::SolverKind solver_kind(int64_t index) {
  const fem_reference::SolverKind kinds[] = {fem_reference::SolverKind::Auto, fem_reference::SolverKind::Direct,
                                             fem_reference::SolverKind::Amg, fem_reference::SolverKind::Mg};
  return kinds[index];
}

/// The sweep's problem: a unit square (cube) of cells^dim elements, clamped at y = 0, 1 MN/m
/// (N/m^2) downwards on y = 1.
fem_reference::FemProblem box_problem(int dim, int degree, int cells, int refine, int64_t solver) {
  fem_reference::FemProblem p;
  p.name = "sweep";
  fem_reference::Box box;
  box.cells = {cells, cells, dim == 3 ? cells : 0};
  p.box = box;
  p.supports.push_back({"y0", fem_reference::SupportKind::Clamped, {}});
  p.tractions.push_back({"y1", {0.0, -1e6, 0.0}, {}});
  p.options.degree = degree;
  p.options.refine = refine;
  p.options.solver = solver_kind(solver);
  return p;
}

void BM_Sweep(benchmark::State& state) {
  auto p = box_problem(int(state.range(0)), int(state.range(1)), int(state.range(2)), int(state.range(3)), state.range(4));
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

/// Case 0, 1: the seed plate, block3d at mesh size h = 8 mm / n with an 8 mm load patch (n cells
/// wide; both cases' sizes and the patch's position are multiples of such an h). Case 2, 3: the
/// sweep's unit square, cube of n cells per side (box_problem, no gmsh).
fem_reference::FemProblem small_problem(int which, int degree, int n, int64_t solver) {
  if (which >= 2) return box_problem(which, degree, n, 0, solver);
  const char* cases[] = {WORKBENCH_SOURCE_DIR "/cases/seed_plate.toml", WORKBENCH_SOURCE_DIR "/cases/block3d.toml"};
  const workbench::CaseFile file{std::filesystem::path(cases[which])};
  auto p = fem_reference::problem_from_case(file);
  p.mesh_parameters["h"] = 0.008 / n;
  p.mesh_parameters["lw"] = 0.008;
  p.options.degree = degree;
  p.options.solver = solver_kind(solver);
  return p;
}

/// Small/case/degree/n/solver/runs: one warm-up, then `runs` calls; of each call the wall seconds
/// without its mesh_seconds (set-up, assembly, solve, stresses, displacements) and its cpu_seconds,
/// min and median; the phases of the fastest call; the largest displacement component (u_max).
void BM_Small(benchmark::State& state) {
  const auto p = small_problem(int(state.range(0)), int(state.range(1)), int(state.range(2)), state.range(3));
  fem_reference::FemResult r = fem_reference::solve_fem(p), best;
  std::vector<double> wall, cpu;
  for (auto _ : state) {
    for (int k = 0; k < std::max<int64_t>(state.range(4), 1); ++k) {
      const auto start = std::chrono::steady_clock::now();
      r = fem_reference::solve_fem(p);
      wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - r.mesh_seconds);
      cpu.push_back(r.cpu_seconds);
      if (wall.back() <= *std::min_element(wall.begin(), wall.end())) best = r;
    }
  }
  double u_max = 0;
  for (double u : r.node_displacement) u_max = std::max(u_max, std::abs(u));
  state.SetLabel(r.solver);
  state.counters["dofs"] = double(r.n_dofs);
  for (auto* times : {&wall, &cpu}) std::sort(times->begin(), times->end());
  state.counters["min_s"] = wall.front();
  state.counters["median_s"] = wall[wall.size() / 2];
  state.counters["cpu_min_s"] = cpu.front();
  state.counters["cpu_median_s"] = cpu[cpu.size() / 2];
  state.counters["setup_s"] = best.setup_seconds;
  state.counters["assemble_s"] = best.assemble_seconds;
  state.counters["solve_s"] = best.solve_seconds;
  state.counters["output_s"] = best.output_seconds;
  state.counters["iterations"] = r.iterations;
  state.counters["u_max"] = u_max;
}

/// Parses "--name=a,b,c" into integers; empty when `arg` is not that option.
std::vector<int64_t> option_list(const std::string& arg, const std::string& name) {
  std::vector<int64_t> a;
  if (arg.rfind(name, 0) != 0) return a;
  std::stringstream in(arg.substr(name.size()));
  for (std::string item; std::getline(in, item, ',');) a.push_back(std::stoll(item));
  return a;
}

}  // namespace

BENCHMARK(BM_PlateQ1)->DenseRange(0, 4)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_PlateQ2)->DenseRange(0, 3)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_PlateQ1Mg)->DenseRange(0, 4)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_PlateQ2Mg)->DenseRange(0, 3)->Unit(benchmark::kSecond)->Iterations(1);
// The issue-38 ladder: both cases, Q1 and Q2, h = 8, 4, 2 mm, auto, 5 warm runs each.
BENCHMARK(BM_Small)->ArgsProduct({{0, 1}, {1, 2}, {1, 2, 4}, {0}, {5}})->Unit(benchmark::kMillisecond)->Iterations(1);

/// Standard Google Benchmark main, plus `--sweep=dim,degree,cells,refine,solver` (repeatable):
/// registers Sweep/<those five> (bench/fem/solver_sweep.py runs one per process), and
/// `--small=case,degree,n,solver,runs` (repeatable): Small/<those five>.
int main(int argc, char** argv) {
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto sweep = option_list(arg, "--sweep="), small = option_list(arg, "--small=");
    if (sweep.empty() && small.empty()) {
      rest.push_back(argv[i]);
      continue;
    }
    if (sweep.size() + small.size() != 5) {
      std::fprintf(stderr, "fem_bench: --sweep needs dim,degree,cells,refine,solver; --small case,degree,n,solver,runs\n");
      return 2;
    }
    benchmark::RegisterBenchmark(sweep.empty() ? "Small" : "Sweep", sweep.empty() ? BM_Small : BM_Sweep)
        ->Args(sweep.empty() ? small : sweep)
        ->Unit(benchmark::kSecond)
        ->Iterations(1);
  }
  int n = int(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

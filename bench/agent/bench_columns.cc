// Throughput of the columns rule set (bending; results in docs/performance.md).
//
//   taskset -c 1 build/bench/columns_bench --benchmark_counters_tabular=true
//
// Cantilever/n: a 5n x n beam of 1 mm agents clamped at x = 0, one load down on the top of its
// last column: the statics, the bonded thrust (none for a clamp), Navier and Jourawski per column
// and the march of the displacement. Supported/n: the same beam on two supports (the bottom faces
// of its end columns), the load at midspan: the thrust's two scans too. Cantilever3D/n: a 5n x n x
// n prism of 1 mm cubes clamped at x = 0, the load down on the top of its last slab (sections of n
// x n agents, Jourawski per level). Counter: agents/s, flat in n when the cost is linear in the
// agents.
#include <agent/load_transfer.h>

#include <benchmark/benchmark.h>

using namespace agent;

namespace {

void columns(benchmark::State& state, bool supports) {
  const int n = int(state.range(0)), nx = 5 * n;
  Grid g = Grid::box(2, {nx, n, 1}, Eigen::Vector3d::Constant(1e-3), 1e-3);
  if (supports)
    g.set_boundary({{g.index(0, 0, 0), direction(1, false)}, {g.index(nx - 1, 0, 0), direction(1, false)}}, Boundary::Rigid);
  else
    g.set_boundary(g.box_side(direction(0, false)), Boundary::Rigid);
  LoadTransfer m(g, {206e9, 0.3}, Coefficients{}, RuleSet::Columns);
  const std::vector<EntryLoad> loads{{g.index(supports ? nx / 2 : nx - 1, n - 1, 0), direction(1, false), 1.0}};
  for (auto _ : state) {
    m.solve(loads);
    benchmark::DoNotOptimize(m.displacement().data());
  }
  const double agents = double(g.agent_count());
  state.counters["agents/s"] = benchmark::Counter(agents, benchmark::Counter::kIsIterationInvariantRate);
}

void Cantilever3D(benchmark::State& state) {
  const int n = int(state.range(0)), nx = 5 * n;
  Grid g = Grid::box(3, {nx, n, n}, Eigen::Vector3d::Constant(1e-3));
  g.set_boundary(g.box_side(direction(0, false)), Boundary::Rigid);
  LoadTransfer m(g, {206e9, 0.3}, Coefficients{}, RuleSet::Columns);
  std::vector<EntryLoad> loads;
  for (int k = 0; k < n; ++k) loads.push_back({g.index(nx - 1, n - 1, k), direction(1, false), 1.0 / n});
  for (auto _ : state) {
    m.solve(loads);
    benchmark::DoNotOptimize(m.displacement().data());
  }
  state.counters["agents/s"] = benchmark::Counter(double(g.agent_count()), benchmark::Counter::kIsIterationInvariantRate);
}

void Cantilever(benchmark::State& state) { columns(state, false); }
void Supported(benchmark::State& state) { columns(state, true); }

}  // namespace

BENCHMARK(Cantilever)->Arg(40)->Arg(80)->Arg(160)->Arg(320)->Unit(benchmark::kMillisecond);
BENCHMARK(Supported)->Arg(40)->Arg(80)->Arg(160)->Arg(320)->Unit(benchmark::kMillisecond);
BENCHMARK(Cantilever3D)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();

// Throughput of the directional rule set (the project's extension; results in docs/performance.md).
//
//   taskset -c 1 build/bench/directional_bench --benchmark_counters_tabular=true
//
// Directional2D/n: one load into the top of an n x n plate of 1 mm agents on a rigid base, the
// default (calibrated) coefficients, 32 directions; Directional3D/n: an n^3 block, 16 x 16
// directions. Counters: moves/s (packets moved per second: the cost is agents reached times
// directions), reached (agents), moves per agent reached.
#include <agent/load_transfer.h>

#include <benchmark/benchmark.h>

using namespace agent;

namespace {

void directional(benchmark::State& state, int dim, int directions) {
  const int n = int(state.range(0));
  Grid g = Grid::box(dim, {n, n, dim == 3 ? n : 1}, Eigen::Vector3d::Constant(1e-3), 1e-3);
  g.set_boundary(g.box_side(direction(1, false)), Boundary::Rigid);
  Coefficients k;
  k.directional.directions = directions;
  LoadTransfer m(g, {206e9, 0.3}, k, RuleSet::Directional);
  const std::vector<EntryLoad> loads{
      {g.index(n / 2, n - 1, dim == 3 ? n / 2 : 0), direction(1, false), 1.0}};
  for (auto _ : state) {
    m.solve(loads);
    benchmark::DoNotOptimize(m.face_forces().data());
  }
  const auto& d = m.diagnostics();
  state.counters["moves/s"] = benchmark::Counter(double(d.packet_moves), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["reached"] = double(d.agents_generated);
  state.counters["moves/agent"] = double(d.packet_moves) / double(d.agents_generated);
}

void Directional2D(benchmark::State& state) { directional(state, 2, 32); }
void Directional3D(benchmark::State& state) { directional(state, 3, 16); }

}  // namespace

BENCHMARK(Directional2D)->Arg(200)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(Directional3D)->Arg(32)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();

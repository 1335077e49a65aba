// Throughput of the directional rule set (the project's extension; results in docs/performance.md).
//
//   taskset -c 1 build/bench/directional_bench --benchmark_counters_tabular=true
//
// Directional2D/n: one load into the top of an n x n plate of 1 mm agents on a rigid base, the
// default (calibrated) coefficients, 32 directions, turning paths (the default);
// Directional2DMirror/n: the same on mirrored straight paths; Directional3D/n: an n^3 block,
// 16 x 16 directions. Counters: moves/s (packets moved per second; turning paths: a row's deposit
// into one agent, all directions together, so 1 per agent reached; the cost is that times the
// directions, one Gaussian cdf per direction and agent edge), reached (agents), moves per agent
// reached. Directional2DStress/n: the turning plate's stress components alone (the
// shear, the tie scan, the base layer: directional_stress_components), per agent;
// Directional2DStressHoles/n: the same on a perforated plate, a hole of 4 x 4 agents every 20
// agents each way ((n / 20)^2 holes, each one's Kirsch shear over the agents within 10 radii):
// linear in the agents if its agents/s stay the same as n grows. Directional3DStress/n: the
// n^3 block's stress components alone (the shears, each layer's solve, the base layer), per agent:
// its layers are alike, so one factorisation serves them all; Directional3DStressUnlikeLayers/n:
// one agent of each layer made air, each elsewhere, so every layer is factorised afresh.
#include <agent/fields.h>
#include <agent/load_transfer.h>
#include <agent/stress_components.h>

#include <benchmark/benchmark.h>

using namespace agent;

namespace {

void directional(benchmark::State& state, int dim, int directions, Paths paths = Paths::Turning) {
  const int n = int(state.range(0));
  Grid g = Grid::box(dim, {n, n, dim == 3 ? n : 1}, Eigen::Vector3d::Constant(1e-3), 1e-3);
  g.set_boundary(g.box_side(direction(1, false)), Boundary::Rigid);
  Coefficients k;
  k.directional.directions = directions;
  k.directional.paths = paths;
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
void Directional2DMirror(benchmark::State& state) { directional(state, 2, 32, Paths::Mirror); }
void Directional3D(benchmark::State& state) { directional(state, 3, 16); }

void stress_components(benchmark::State& state, int dim, bool holes) {
  const int n = int(state.range(0));
  Grid g = Grid::box(dim, {n, n, dim == 3 ? n : 1}, Eigen::Vector3d::Constant(1e-3), 1e-3);
  g.set_boundary(g.box_side(direction(1, false)), Boundary::Rigid);
  if (holes && dim == 2)
    for (int j0 = 8; j0 + 4 < n - 8; j0 += 20)
      for (int i0 = 8; i0 + 4 < n - 8; i0 += 20)
        for (int j = j0; j < j0 + 4; ++j)
          for (int i = i0; i < i0 + 4; ++i) g.make_air(g.index(i, j, 0));
  if (holes && dim == 3)  // one agent of each layer below the top, each elsewhere: no two alike
    for (int j = 0; j + 1 < n; ++j) g.make_air(g.index(j, j, n - 1 - j));
  const Coefficients k;
  LoadTransfer m(g, {206e9, 0.3}, k, RuleSet::Directional);
  const std::vector<EntryLoad> loads{{g.index(n / 2, n - 1, dim == 3 ? n / 2 : 0), direction(1, false), 1.0}};
  m.solve(loads);
  const auto normal = agent_stresses(g, m.face_forces());
  for (auto _ : state) {
    const auto s = directional_stress_components(g, normal, m.shear_stress(), m.balance_slopes(), k.directional, 0.3, loads);
    benchmark::DoNotOptimize(s.sigma.data());
  }
  state.counters["agents/s"] = benchmark::Counter(double(g.count()), benchmark::Counter::kIsIterationInvariantRate);
  if (holes && dim == 2) state.counters["holes"] = double(enclosed_holes(g).size());
}

void Directional2DStress(benchmark::State& state) { stress_components(state, 2, false); }
void Directional2DStressHoles(benchmark::State& state) { stress_components(state, 2, true); }
void Directional3DStress(benchmark::State& state) { stress_components(state, 3, false); }
void Directional3DStressUnlikeLayers(benchmark::State& state) { stress_components(state, 3, true); }

}  // namespace

BENCHMARK(Directional2D)->Arg(200)->Arg(400)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(Directional2DMirror)->Arg(200)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(Directional2DStress)->Arg(200)->Arg(400)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(Directional2DStressHoles)->Arg(200)->Arg(400)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(Directional3DStress)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);
BENCHMARK(Directional3DStressUnlikeLayers)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);
BENCHMARK(Directional3D)->Arg(32)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();

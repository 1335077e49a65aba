// Throughput and locality of the agent load transfer (results in docs/performance.md).
//
//   build/bench/agent_bench --benchmark_counters_tabular=true
//
// - Agent2D/n, Agent3D/n: a load that reaches (nearly) every agent of an n x n (x n) grid:
//   conserving rule set, gamma = 1e-300 (just above denormals, which are slow and meaningless).
// - Reach2D/4096/percent: the same grid, gamma chosen so that the load reaches `percent` % of it;
//   the seed's claim is that cost follows reach, not the body.
// - Band2D/n/tiled, Band3D/n/tiled: a connected but sparse body, a diagonal band 16 agents wide
//   (3D: and 8 deep) across an n x n (x n) box, loaded at its top, dense (tiled = 0) and laid out
//   on tiles (tiled = 1, agent::Tiles): the same work; memory follows the box or the tiles.
// Counters: updates/s (agent visits per second), agents reached, bytes per agent (agents: the
// slots that are not air).
#include <agent/load_transfer.h>

#include <benchmark/benchmark.h>

#include <cmath>

using namespace agent;

namespace {

Grid plate(int dim, int n) {
  Grid g = Grid::box(dim, {n, n, dim == 3 ? n : 1}, Eigen::Vector3d::Constant(1e-3), 1e-3);
  g.set_boundary(g.box_side(direction(1, false)), Boundary::Rigid);
  return g;
}

EntryLoad top_centre(const Grid& g) {
  return {g.index(g.cells[0] / 2, g.cells[1] - 1, g.dim == 3 ? g.cells[2] / 2 : 0), direction(1, false), 1.0};
}

Coefficients coefficients(double gamma) {
  Coefficients k;
  k.gamma = gamma;
  k.threshold = agent::Threshold::Absolute;  // the seed's absolute threshold
  return k;
}

void report(benchmark::State& state, const LoadTransfer& m) {
  const auto& d = m.diagnostics();
  state.counters["updates/s"] =
      benchmark::Counter(double(d.agent_updates), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["reached"] = double(d.agents_generated);
  const double agents = double(m.grid().agent_count());
  state.counters["reach_%"] = 100.0 * double(d.agents_generated) / agents;
  state.counters["B/agent"] = double(m.memory_bytes()) / agents;
}

void full_reach(benchmark::State& state, int dim) {
  const Grid g = plate(dim, int(state.range(0)));
  LoadTransfer m(g, {206e9, 0.3}, coefficients(1e-300), RuleSet::Conserving);
  const std::vector<EntryLoad> loads{top_centre(g)};
  for (auto _ : state) {
    m.solve(loads);
    benchmark::DoNotOptimize(m.face_forces().data());
  }
  report(state, m);
}

void Agent2D(benchmark::State& state) { full_reach(state, 2); }
void Agent3D(benchmark::State& state) { full_reach(state, 3); }

/// gamma that makes the load reach `percent` % of the grid (bisection on log gamma).
double gamma_for_reach(const Grid& g, double percent) {
  double lo = -300, hi = 0;
  LoadTransfer m(g, {206e9, 0.3}, coefficients(1), RuleSet::Conserving);
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    m = LoadTransfer(g, {206e9, 0.3}, coefficients(std::pow(10.0, mid)), RuleSet::Conserving);
    m.solve({top_centre(g)});
    const double reach = 100.0 * double(m.diagnostics().agents_generated) / double(g.count());
    (reach > percent ? lo : hi) = mid;
  }
  return std::pow(10.0, hi);
}

void Reach2D(benchmark::State& state) {
  const Grid g = plate(2, int(state.range(0)));
  const double gamma = state.range(1) >= 100 ? 1e-300 : gamma_for_reach(g, double(state.range(1)));
  LoadTransfer m(g, {206e9, 0.3}, coefficients(gamma), RuleSet::Conserving);
  const std::vector<EntryLoad> loads{top_centre(g)};
  for (auto _ : state) {
    m.solve(loads);
    benchmark::DoNotOptimize(m.face_forces().data());
  }
  report(state, m);
  state.counters["gamma"] = gamma;
}

// The diagonal band: agents (i, j, k) with 0 <= i - j < 16 (and n/2 - 4 <= k < n/2 + 4 in 3D),
// its base rigid; the load enters the top row's rightmost agent.
void band(benchmark::State& state, int dim) {
  const int n = int(state.range(0));
  Grid g = Grid::box(dim, {n, n, dim == 3 ? n : 1}, Eigen::Vector3d::Constant(1e-3), 1e-3);
  for (std::size_t c = 0; c < g.count(); ++c) {
    const auto x = g.coords(c);
    const bool in = x[0] - x[1] >= 0 && x[0] - x[1] < 16 && (dim == 2 || std::abs(x[2] - n / 2) < 4);
    if (!in) g.make_air(c);
  }
  g.set_boundary(g.box_side(direction(1, false)), Boundary::Rigid);
  if (state.range(1)) g = tile(g);
  LoadTransfer m(g, {206e9, 0.3}, coefficients(1e-300), RuleSet::Conserving);
  const std::vector<EntryLoad> loads{{g.index(n - 1, n - 1, dim == 3 ? n / 2 : 0), direction(1, false), 1.0}};
  for (auto _ : state) {
    m.solve(loads);
    benchmark::DoNotOptimize(m.face_forces().data());
  }
  report(state, m);
}

void Band2D(benchmark::State& state) { band(state, 2); }
void Band3D(benchmark::State& state) { band(state, 3); }

}  // namespace

BENCHMARK(Band2D)->Args({2048, 0})->Args({2048, 1})->Unit(benchmark::kMillisecond);
BENCHMARK(Band3D)->Args({256, 0})->Args({256, 1})->Unit(benchmark::kMillisecond);
BENCHMARK(Agent2D)->Arg(200)->Arg(512)->Arg(1024)->Arg(2048)->Arg(4096)->Unit(benchmark::kMillisecond);
BENCHMARK(Agent3D)->Arg(32)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMillisecond);
BENCHMARK(Reach2D)->Args({4096, 1})->Args({4096, 10})->Args({4096, 100})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

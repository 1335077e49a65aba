// Cost of the cyclic transfer (readings 1, 2 and 6 of the patent rule set; docs/performance.md).
//
//   taskset -c 1 build/bench/cyclic_bench --benchmark_counters_tabular=true
//
// Cyclic/h_um/gamma_exp/fitted: the seed plate (200 mm x 200 mm x 2 mm, rigid base, 2 N on a patch
// of two agents at the top centre) with agents of h_um micrometres, gamma = 10^-gamma_exp N, the
// seed's coefficients (fitted = 0) or the prototype fit (alpha1 0.53, alpha2 0.49,
// alpha3 0.49; fitted = 1). Counters: updates (work-list items processed), updates/s, reached
// agents, waves (transfers in the longest chain above gamma, plus one).
#include <agent/load_transfer.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

using namespace agent;

namespace {

void Cyclic(benchmark::State& state) {
  const double h = double(state.range(0)) * 1e-6;
  const int n = int(std::lround(0.2 / h));
  Grid g = Grid::box(2, {n, n, 1}, Eigen::Vector3d(h, h, 1), 0.002);
  g.set_boundary(g.box_side(direction(1, false)), Boundary::Rigid);
  Coefficients k;
  k.gamma = std::pow(10.0, -double(state.range(1)));
  k.threshold = agent::Threshold::Absolute;
  if (state.range(2)) {
    k.alpha1 = 0.53;
    k.alpha2 = 0.49;
    k.alpha3 = 0.49;
  }
  Readings r;
  r.non_compounding_entry = r.every_agent_all_operations = r.boundaries_return = true;
  LoadTransfer m(g, {206e9, 0.3}, k, RuleSet::Patent, r);
  const std::vector<EntryLoad> loads{{g.index(n / 2 - 1, n - 1, 0), direction(1, false), 1.0},
                                     {g.index(n / 2, n - 1, 0), direction(1, false), 1.0}};
  for (auto _ : state) {
    m.solve(loads);
    benchmark::DoNotOptimize(m.face_forces().data());
  }
  const auto& d = m.diagnostics();
  state.counters["updates"] = double(d.agent_updates);
  state.counters["updates/s"] = benchmark::Counter(double(d.agent_updates), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["reached"] = double(d.agents_generated);
  state.counters["waves"] = double(*std::max_element(m.generation().begin(), m.generation().end()) + 1);
}

}  // namespace

BENCHMARK(Cyclic)->ArgsProduct({{5000, 2000}, {3, 5}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();

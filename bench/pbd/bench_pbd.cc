// PBD angle bending benchmarks (docs/performance.md, "PBD angle bending"):
//  - angle-constraint projections per second on one core (Gauss-Seidel sweep over a sheet's
//    constraints, signed and unsigned form);
//  - steps per second of a 100,489-node (316 x 316 cells) triangulated sheet, 1 substep x 1
//    iteration, hanging under gravity, with 1 and 2 threads (blocks of 256 constraints, graph-coloured, OpenMP),
//    150 steps from rest each run.
#include <pbd/model.h>
#include <pbd/solver.h>

#include <benchmark/benchmark.h>

#include <cmath>

using pbd::Vec3;

namespace {

pbd::Model sheet_model(int n, bool planar) {
  auto mesh = pbd::Mesh::grid(n, n, 1.0 / n, true);
  // A gentle out-of-plane wave, so that the 3D angles are not all straight (the skipped case).
  if (!planar)
    for (auto& p : mesh.points) p[2] = 0.02 * std::sin(7 * p[0]) * std::cos(5 * p[1]);
  std::vector<int> pinned;
  for (int i = 0; i <= n; ++i) pinned.push_back(n * (n + 1) + i);  // top edge
  pbd::ModelOptions o;
  o.bending_compliance = 1e-3;
  if (planar) o.planar_axis = Vec3::UnitZ();
  return pbd::build_model(mesh, pinned, o);
}

void perturb(pbd::Model& m) {
  for (std::size_t i = 0; i < m.particles.size(); ++i)
    if (m.particles.w[i] > 0) m.particles.x[i] += Vec3(1e-3 * std::sin(0.37 * i), 1e-3 * std::cos(0.11 * i), 1e-3 * std::sin(0.05 * i));
}

/// One Gauss-Seidel sweep over all angle constraints per iteration, in the solver's order.
void BM_AngleProjections(benchmark::State& state) {
  const bool planar = state.range(1) != 0;
  auto m = sheet_model(int(state.range(0)), planar);
  if (planar)
    for (auto& x : m.particles.x) x[2] = 0;
  perturb(m);
  std::vector<double> lambda(m.angles.size(), 0.0);
  auto* x = m.particles.x.data();
  const double* w = m.particles.w.data();
  const Vec3* axis = m.axis_ptr();
  const double inv_h2 = 1e4;
  for (auto _ : state) {
    for (std::size_t c = 0; c < m.angles.size(); ++c) {
      const auto& a = m.angles[c];
      pbd::project_angle(x[a.best], x[a.k], x[a.i], w[a.best], w[a.k], w[a.i], a.rest_cos, a.rest_sin,
                         a.compliance * inv_h2, lambda[c], axis);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(m.angles.size()));
  state.counters["constraints"] = double(m.angles.size());
  state.counters["ns_per_projection"] =
      benchmark::Counter(double(m.angles.size()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_AngleProjections)->ArgsProduct({{30, 316}, {0, 1}})->ArgNames({"n", "signed"})->Unit(benchmark::kMillisecond);

/// Frames of the 100k-node sheet: 1 substep, 1 iteration, distance + angle constraints.
void BM_SheetStep(benchmark::State& state) {
  auto m = sheet_model(316, false);
  pbd::Solver solver(m);
  pbd::StepSettings s;
  s.dt = 1.0 / 60;
  s.gravity = Vec3(0, 0, -9.81);
  s.threads = int(state.range(0));
  for (auto _ : state) solver.step(s);
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(m.angles.size() + m.distances.size()));
  state.counters["nodes"] = double(m.particles.size());
  state.counters["angles"] = double(m.angles.size());
  state.counters["distances"] = double(m.distances.size());
  state.counters["colours"] = double(m.angle_colouring.colours() + m.distance_colouring.colours());
  state.counters["blocks"] = double(m.angle_colouring.blocks() + m.distance_colouring.blocks());
  state.counters["steps_per_s"] = benchmark::Counter(1, benchmark::Counter::kIsIterationInvariantRate);
}
// A fixed count of steps: with 1 substep x 1 iteration the sheet is far from converged and
// stretches without bound as it falls, and a step grows dearer as it does (the share of angle
// constraints past the Taylor range of the fast atan2 is 0, 47 % and 81 % at steps 0, 100 and
// 200; a step at 100-200 costs 1.2-1.4x one of the first 50), so with a time budget a faster run
// would be timed over a later, dearer part of the fall. The same 150 steps for every thread count
// make the ratio between them the speed-up (docs/performance.md, "Every core").
BENCHMARK(BM_SheetStep)->Arg(1)->Arg(2)->ArgName("threads")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(150);

}  // namespace

BENCHMARK_MAIN();

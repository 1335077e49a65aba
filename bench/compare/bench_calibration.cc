// A four-coefficient fit (alpha1, alpha2, alpha3, beta; patent rule set) on the seed plate at 2 mm
// agents against FEM. FEM is solved once, outside the timing, as
// `workbench calibrate` does. FourCoefficientFit: 8 starts, on 1 and 2 threads (the starts spread
// over the cores); OneStartFourCases: one start on four cases (the seed plate four times), on 1 and
// 2 threads (each evaluation's cases spread over the cores).
//
//   build/bench/calibration_bench
#include <compare/calibration.h>
#include <fem_reference/fem_case.h>

#include <benchmark/benchmark.h>

namespace {

compare::CalibrationCase seed_plate() {
  workbench::CaseFile file(WORKBENCH_SOURCE_DIR "/cases/seed_plate.toml");
  compare::CalibrationCase c;
  c.name = "seed_plate";
  c.study = agent_study::load_agent_study(file);
  const auto fem = fem_reference::solve_fem(fem_reference::problem_from_case(file));
  c.reference = compare::fem_on_grid(c.study.mesh, fem, "seed_plate");
  return c;
}

compare::CalibrationOptions four_coefficients(int starts, int threads) {
  compare::CalibrationOptions o;
  o.rules = agent::RuleSet::Patent;
  const std::array<double, 5> start{0.5, 0.5, 0.25, 0.5, 1e-3};
  for (int i = 0; i < 5; ++i) o.parameters[i] = {agent::kCoefficients[i].name, i < 4, start[i], 0.0, 1.0};
  o.parameters[4].hi = 1e-2;
  o.starts = starts;
  o.max_evaluations = 400;
  o.threads = threads;
  return o;
}

void FourCoefficientFit(benchmark::State& state) {
  static const std::vector<compare::CalibrationCase> cases{seed_plate()};
  const auto o = four_coefficients(8, int(state.range(0)));
  compare::CalibrationResult r;
  for (auto _ : state) r = compare::calibrate(cases, o);
  state.counters["evaluations"] = double(r.evaluations);
  state.counters["objective_start"] = r.objective_start;
  state.counters["objective_fitted"] = r.objective_best;
}

void OneStartFourCases(benchmark::State& state) {
  static const std::vector<compare::CalibrationCase> cases = [] {
    std::vector<compare::CalibrationCase> four(4, seed_plate());
    for (int i = 0; i < 4; ++i) four[i].name += "_" + std::to_string(i);
    return four;
  }();
  const auto o = four_coefficients(1, int(state.range(0)));
  compare::CalibrationResult r;
  for (auto _ : state) r = compare::calibrate(cases, o);
  state.counters["evaluations"] = double(r.evaluations);
  state.counters["objective_fitted"] = r.objective_best;
}

}  // namespace

BENCHMARK(FourCoefficientFit)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(OneStartFourCases)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

BENCHMARK_MAIN();

// The agent model's whole solve from an imported mesh (issue 38): set-up of the transfer model,
// the transfer, every stress component, the strains and the node displacements at the full load,
// i.e. agent_study::transfer_model(study) + agent_study::evaluate(study, model, 1.0). The mesh is
// imported once, outside the timing, and solved once as a warm-up (tables built, code paged in).
// Results in docs/performance.md ("Issue 38").
//
//   taskset -c 1 build/bench/solve_bench --benchmark_filter='^SeedPlateDirectional$'
//     --benchmark_repetitions=3 --benchmark_min_time=0.2   (one command line)
//
// One case per process: which cases ran before moves glibc's thresholds for giving freed memory
// back, and on this project's virtual machines a fresh page costs 14-80 us. Run also with
// GLIBC_TUNABLES=glibc.malloc.trim_threshold=4000000000:glibc.malloc.mmap_threshold=4000000000
// (freed memory kept: the computation without the page faults).
//
// Cases (cases/): SeedPlateDirectional (2D, 2 mm, 10,000 agents), Block3dDirectional (block3d.toml
// with rule_set = "directional" at its defaults, 2 mm cubes, 8,000 agents), and the seed's rule
// sets on the same meshes, SeedPlatePatent (seed_plate.toml) and Block3dConserving (block3d.toml).
// Counters: agents, and moves (the transfer's packet moves or agent updates: work that does not
// depend on the machine).
#include <agent_study.h>

#include <benchmark/benchmark.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace {

const std::string kCases = WORKBENCH_SOURCE_DIR "/cases/";

/// The case file's text with `from` replaced by `to` (a rule set named in place of another).
std::string edited(const std::string& name, const std::string& from, const std::string& to) {
  std::ifstream in(kCases + name);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const auto at = s.find(from);
  if (at == std::string::npos) throw std::runtime_error(name + ": no '" + from + "'");
  return s.replace(at, from.size(), to);
}

/// The case's study, with one solve as a warm-up (tables built once per process, pages touched).
agent_study::AgentStudy study_of(const workbench::CaseFile& file) {
  auto study = agent_study::load_agent_study(file);
  auto model = agent_study::transfer_model(study);
  agent_study::evaluate(study, model, 1.0);
  return study;
}

/// Each case's study, imported once (static: shared by the repetitions).
const agent_study::AgentStudy& seed_plate_directional() {
  static const auto s = study_of(workbench::CaseFile(kCases + "seed_plate_directional.toml"));
  return s;
}
const agent_study::AgentStudy& seed_plate_patent() {
  static const auto s = study_of(workbench::CaseFile(kCases + "seed_plate.toml"));
  return s;
}
const agent_study::AgentStudy& block3d_conserving() {
  static const auto s = study_of(workbench::CaseFile(kCases + "block3d.toml"));
  return s;
}
const agent_study::AgentStudy& block3d_directional() {
  static const auto s = study_of(workbench::CaseFile(
      edited("block3d.toml", "rule_set = \"conserving\"\ngamma = 1.0e-4", "rule_set = \"directional\""),
      kCases + "block3d_directional.toml"));
  return s;
}

void whole_solve(benchmark::State& state, const agent_study::AgentStudy& study) {
  agent::Diagnostics d;
  for (auto _ : state) {
    auto model = agent_study::transfer_model(study);
    const auto s = agent_study::evaluate(study, model, 1.0);
    benchmark::DoNotOptimize(s.displacement.data());
    d = s.diagnostics;
  }
  state.counters["agents"] = double(study.mesh.cell_of_element.size());
  state.counters["moves"] = double(d.packet_moves + d.agent_updates);
}

void SeedPlateDirectional(benchmark::State& state) { whole_solve(state, seed_plate_directional()); }
void Block3dDirectional(benchmark::State& state) { whole_solve(state, block3d_directional()); }
void SeedPlatePatent(benchmark::State& state) { whole_solve(state, seed_plate_patent()); }
void Block3dConserving(benchmark::State& state) { whole_solve(state, block3d_conserving()); }

}  // namespace

BENCHMARK(SeedPlateDirectional)->Unit(benchmark::kMillisecond);
BENCHMARK(Block3dDirectional)->Unit(benchmark::kMillisecond);
BENCHMARK(SeedPlatePatent)->Unit(benchmark::kMillisecond);
BENCHMARK(Block3dConserving)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();

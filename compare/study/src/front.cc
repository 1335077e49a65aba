// The cost-accuracy front (docs/front.md), in steps: read the case, solve the reference once, run
// the agents' ladder and the FEM's ladder (each point a warm-up, then N timed runs), judge, write.
#include <compare/front.h>
#include <compare/compare_study.h>

#include "agent_compare.h"
#include "front_files.h"
#include "front_ladder.h"
#include "report.h"

#include <fem_reference/mpi.h>
#include <schema/front_options.h>
#include <workbench/case_edit.h>
#include <workbench/error.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ostream>
#include <sstream>

namespace compare {

namespace fs = std::filesystem;
using namespace agent_compare;
using workbench::Error;

namespace {

/// The metric the log shows for every point as it runs.
const std::string kHeadline = "far.sigma_y.rel_l2";

/// What every point of the front is scored against.
struct FrontContext {
  const workbench::CaseFile& file;
  const schema::FrontOptions& options;
  const AgentCompareInput& in;
  const Reference& reference;
  double mask = 0;
  double size = 0;  ///< the case's own agent size [m] (its size parameter)
  std::ostream& log;
};

/// The point's error metrics against the reference (the same code as `workbench compare`'s), and
/// the reference's own error per metric into `floors`.
void score(const FrontContext& c, const GridFields& fields, FrontPoint& p, std::map<std::string, double>* floors) {
  CompareOutcome scored;
  add_field_scopes(scored, c.in, {&fields, &c.reference.fields, &c.reference.estimate_fields, nullptr}, c.mask);
  for (const auto& m : scored.metrics) {
    p.errors[m.name] = m.value;
    if (floors) (*floors)[m.name] = m.reference_error;
  }
}

std::string millimetres(double metres) {
  std::ostringstream s;
  s << 1e3 * metres << " mm";
  return s.str();
}

/// The agent study at `factor` times the case's size under `rules`: the case's own study at its
/// own size and rule set, else the case with those two keys changed (workbench/case_edit.h, on its
/// text: a case may come from Python, not a file), meshed anew.
agent_study::AgentStudy agent_study_at(const FrontContext& c, double factor, agent::RuleSet rules) {
  if (factor == 1 && rules == c.in.study.rules) return c.in.study;
  std::string text = workbench::set_case_keys(c.file.text(), "mesh.parameters",
                                              {{c.options.size_parameter, workbench::toml_number(factor * c.size)}});
  text = workbench::set_case_keys(text, "agent", {{"rule_set", workbench::toml_string(agent::rule_set_name(rules))}});
  workbench::CaseFile derived(text, c.file.path());  // relative paths as the case's own
  return agent_study::load_agent_study(derived);
}

FrontPoint agent_point(const FrontContext& c, double factor, agent::RuleSet rules) {
  FrontPoint p;
  p.model = "agent";
  p.rule_set = agent::rule_set_name(rules);
  p.size = factor * c.size;
  p.label = "agent " + p.rule_set + " " + millimetres(p.size);
  const auto t0 = std::chrono::steady_clock::now();
  const auto study = agent_study_at(c, factor, rules);
  p.work["mesh_seconds"] = report::seconds_since(t0);
  auto model = agent_study::transfer_model(study);
  const auto state = agent_study::evaluate(study, model, 1.0);  // the warm-up: its fields are scored
  time_runs(c.options.runs, p, [&] {
    auto m = agent_study::transfer_model(study);
    agent_study::evaluate(study, m, 1.0);
    return 0.0;
  });
  p.work["agents"] = double(study.mesh.cell_of_element.size());
  p.work["agent_updates"] = double(state.diagnostics.agent_updates);
  p.work["packet_moves"] = double(state.diagnostics.packet_moves);
  const auto& grid = c.in.study.mesh.grid;
  score(c, agents_on_grid(grid, study.mesh.grid, agent_on_grid(study.mesh.grid, state), p.label), p, nullptr);
  const auto modelled = agent_study::stress_model(study);
  for (const auto& [name, error] : p.errors)
    if (!agent_compare::models_metric(name, modelled, grid.dim)) p.not_modelled.insert(name);
  return p;
}

/// The DoFs of the FEM at `factor` times the case's size and `degree`, estimated from the agents.
double estimated_dofs(const FrontContext& c, double factor, int degree) {
  const int dim = c.in.study.mesh.grid.dim;
  return double(c.in.study.mesh.cell_of_element.size()) * std::pow(degree / factor, dim) * dim;
}

/// A FEM result on the case's agent grid, sampled as the reference is (fem_on_grid: the mean of
/// the FEM cells in each agent) where its mesh refines the agents', else at each agent's Gauss points.
GridFields fem_sampled(const FrontContext& c, const fem_reference::FemResult& fem, const std::string& label) {
  try {
    return fem_on_grid(c.in.study.mesh, fem, label);
  } catch (const Error&) {  // a mesh coarser than the agents
    std::array<std::size_t, 2> outside{};
    return fem_at_agents(c.in.study.mesh.grid, fem, outside);
  }
}

FrontPoint fem_point(const FrontContext& c, double factor, int degree) {
  FrontPoint p;
  p.model = "fem";
  p.degree = degree;
  p.size = factor * c.size;
  p.label = "fem Q" + std::to_string(degree) + " " + millimetres(p.size);
  auto problem = c.in.problem;
  problem.mesh_parameters[c.options.size_parameter] = p.size;
  problem.options.degree = degree;
  problem.options.solver = fem_reference::SolverKind::Auto;  // the project's fastest path for the size
  problem.options.refine = 0;
  problem.options.write_vtu = false;
  problem.options.coarser_level = false;
  const auto& grid = c.in.study.mesh.grid;
  problem.probe_points = agent_probe_points(grid);
  const auto warm = fem_reference::solve_fem(problem);  // the warm-up, evaluated at the agents
  p.work["mesh_seconds"] = warm.mesh_seconds;
  problem.probe_points.clear();  // the timed runs: the model's work alone
  time_runs(c.options.runs, p, [&] { return fem_reference::solve_fem(problem).mesh_seconds; });
  p.work["dofs"] = double(warm.n_dofs);
  p.work["cells"] = double(warm.n_active_cells);
  p.work["iterations"] = double(warm.iterations);
  score(c, fem_sampled(c, warm, p.label), p, nullptr);
  return p;
}

std::vector<agent::RuleSet> rule_sets(const FrontContext& c) {
  std::vector<agent::RuleSet> out{c.in.study.rules};
  for (const auto& name : c.options.rule_sets)
    if (std::find(out.begin(), out.end(), *agent::rule_set_named(name)) == out.end())
      out.push_back(*agent::rule_set_named(name));
  return out;
}

void run_ladders(const FrontContext& c, FrontOutcome& out) {
  for (const auto rules : rule_sets(c))
    for (double f : c.options.agent_sizes)
      add_point(out, c.log, "agent " + std::string(agent::rule_set_name(rules)) + " at " + millimetres(f * c.size),
                kHeadline, [&] { return agent_point(c, f, rules); });
  for (int degree : c.options.fem_degrees)
    for (double f : c.options.fem_sizes) {
      const std::string what = "fem Q" + std::to_string(degree) + " at " + millimetres(f * c.size);
      if (estimated_dofs(c, f, degree) > c.options.fem_max_dofs) {
        out.skipped.push_back(what + ": about " + std::to_string(long(estimated_dofs(c, f, degree))) +
                              " DoFs, over front.fem_max_dofs");
        continue;
      }
      add_point(out, c.log, what, kHeadline, [&] { return fem_point(c, f, degree); });
    }
}

/// The case's own size parameter [m], or a case-file error naming the key.
double case_size(const workbench::CaseFile& file, const AgentCompareInput& in, const std::string& parameter) {
  const auto& parameters = in.study.setup.mesh_parameters;
  const auto it = parameters.find(parameter);
  if (it == parameters.end())
    file.root().table("front").fail("size_parameter", "the mesh has no parameter \"" + parameter +
                                                          "\" ([mesh.parameters]) to set the agents' size with");
  if (std::abs(it->second - in.study.mesh.grid.size[0]) > 1e-9 * it->second)
    file.root().table("front").fail("size_parameter", "mesh.parameters." + parameter + " = " +
                                                          workbench::toml_number(it->second) +
                                                          " m is not the agents' size " +
                                                          workbench::toml_number(in.study.mesh.grid.size[0]) + " m");
  return it->second;
}

}  // namespace

std::vector<std::string> front_metrics(int dim) {
  std::vector<std::string> out;
  for (const char* scope : {"far", "body"})
    for (const auto& f : kFields)
      if (f.in(dim)) out.push_back(std::string(scope) + "." + f.name + ".rel_l2");
  return out;
}

void require_one_rank(const workbench::CaseFile& file) {
  if (fem_reference::mpi_size() > 1)  // every rank says so: printed once
    throw fem_reference::CollectiveError(file.path().string() + ": workbench front times each model on one core: "
                                         "run it without mpirun");
}

std::vector<std::string> check_front(const workbench::CaseFile& file) {
  const auto options = schema::read_front_options(file.root());
  if (read_compare_options(file.root()).model != "pbd") return check_compare(file);
  check_pbd_front(file, options);
  return {};
}

FrontOutcome run_front(const workbench::CaseFile& file, const fs::path& dir, std::ostream& log) {
  require_one_rank(file);
  // 1. Read and check everything before running anything.
  const auto options = schema::read_front_options(file.root());
  const auto compare_options = read_compare_options(file.root());
  if (compare_options.model == "pbd") return run_pbd_front(file, options, dir, log);
  const auto in = read_input(file, compare_options);
  for (const auto& w : in.warnings) log << "front: warning: " << w << "\n";
  const double size = case_size(file, in, options.size_parameter);
  front_files::check_gate_names(options.gate, front_metrics(in.study.mesh.grid.dim), file);
  // 2. The reference and its own error, as `workbench compare` solves them (its files in dir/fem).
  auto reference = solve_reference(in.problem, in.reference, in.study.mesh, dir, log);
  estimate_reference_error(reference, in.problem, in.study.mesh, log);
  const FrontContext c{file, options, in, reference, compare_options.mask, size, log};
  // 3. The ladders.
  FrontOutcome out;
  run_ladders(c, out);
  const std::string own = "agent " + std::string(agent::rule_set_name(in.study.rules)) + " " + millimetres(size);
  if (std::none_of(out.points.begin(), out.points.end(), [&](const FrontPoint& p) { return p.label == own; }))
    throw Error(file.path().string() + ": front.agent_sizes: the agents at the case's own size did not run (" +
                (out.skipped.empty() ? std::string("not in the ladder") : out.skipped.front()) + ")");
  out.case_point = own;
  FrontPoint floors;
  score(c, reference.fields, floors, &out.reference_errors);
  // 4. The verdicts, the gate, the files.
  const auto metrics = front_metrics(in.study.mesh.grid.dim);
  out.verdicts = front_verdicts(out.points, metrics, out.reference_errors);
  out.crossovers = front_crossovers(out.points, metrics, out.reference_errors);
  front_files::apply_gate(options.gate, out);
  const front_files::FrontHeader header{
      in.study.setup.title, metrics, {kHeadline, "far.von_mises.rel_l2", "body.displacement.rel_l2"},
      {{"description", reference.options.describe()}, {"dofs", reference.fem.n_dofs},
       {"estimate", reference.estimate.describe()}, {"estimate_dofs", reference.estimate_dofs}}};
  front_files::write(dir, file, header, options, out, log);
  return out;
}

}  // namespace compare

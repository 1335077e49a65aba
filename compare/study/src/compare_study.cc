// The agent comparison (docs/compare.md): the agent method against the converged FEM reference
// on the same body, in named steps: read, run the agent model, solve the reference, sample,
// score, write, draw, summarise.
#include <compare/calibration.h>
#include <compare/compare_study.h>
#include <compare/pbd_compare.h>
#include <compare/reference.h>
#include <compare/same_body.h>

#include "agent_compare.h"
#include "report.h"

#include <agent/voxelize.h>
#include <agent_study.h>
#include <carry_check.h>
#include <fem_reference/fem_case.h>
#include <fem_reference/mpi.h>
#include <workbench/csv_file.h>
#include <workbench/error.h>
#include <workbench/line_log.h>
#include <workbench/vtk_output.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <map>
#include <mutex>
#include <optional>
#include <ostream>
#include <sstream>

namespace compare {

namespace fs = std::filesystem;
using workbench::Error;
using namespace agent_compare;

namespace {

using workbench::open_csv;

using report::seconds_since;

/// The entries of `v` (comps per entry) at the `ids` (in their order) that `keep` marks.
std::vector<double> select(const std::vector<double>& v, int comps, const std::vector<std::size_t>& ids,
                           const std::vector<char>& keep) {
  std::vector<double> out;
  for (std::size_t i : ids)
    if (keep[i]) out.insert(out.end(), v.begin() + i * comps, v.begin() + (i + 1) * comps);
  return out;
}

std::vector<std::string> agent_metric_names(const std::vector<std::string>& line_names, int dim) {
  std::vector<std::string> scopes{"body", "far"};
  scopes.insert(scopes.end(), line_names.begin(), line_names.end());
  std::vector<std::string> names;
  for (const auto& s : scopes) {
    for (const auto& f : kFields)
      if (f.in(dim))
        for (const char* n : {"rel_l2", "rel_max"}) names.push_back(s + "." + f.name + "." + n);
    for (const auto& f : kFields)
      if (f.ratios) {
        names.push_back(s + "." + f.name + ".ratio_median_dev");
        names.push_back(s + "." + f.name + ".masked_fraction");
      }
  }
  for (const char* n : {"agent.equilibrium_dev", "agent.lost_share", "agent.reaction_share", "fem.equilibrium_dev",
                        "agent.reach_fraction", "time.agent_s", "time.fem_s", "time.compare_s", "time.figures_wait_s",
                        "time.total_s"})
    names.push_back(n);
  return names;
}

}  // namespace

std::string GateFailure::describe() const {
  std::ostringstream s;
  if (!refused.empty()) return "carry check: " + refused;
  s << metric << " = " << value;
  if (zero_model)
    s << " is not below the zero model's " << limit << ": worse than predicting zero";
  else
    s << " exceeds " << limit << " by " << value - limit;
  return s.str();
}

void FieldTable::add(const std::string& name, int components, std::vector<double> values, Kind kind) {
  if (columns.empty()) rows = values.size() / std::size_t(components);
  if (values.size() != rows * std::size_t(components))
    throw Error("compare: field " + name + " has " + std::to_string(values.size()) + " values, not " +
                std::to_string(rows) + " x " + std::to_string(components));
  columns.push_back({name, components, std::move(values), kind});
}

std::vector<std::string> metric_names(const CompareOptions& options, const std::vector<std::string>& line_names, int dim) {
  return options.model == "pbd" ? pbd_metric_names() : agent_metric_names(line_names, dim);
}

AgentCompareInput agent_compare::read_input(const workbench::CaseFile& file, const CompareOptions& options) {
  AgentCompareInput in{agent_study::load_agent_study(file), fem_reference::problem_from_case(file), {}, {}, {}, 0, {}, {}, {}};
  const auto& grid = in.study.mesh.grid;
  in.reference = reference_options(options, in.study);
  in.warnings = check_reference_body(file, in.study, in.reference);
  in.loads = load_frames(in.study.mesh, in.study.setup.loads);
  const auto& study = in.study;
  in.stress_model = agent_study::stress_model(study);
  // A line stops at air: one through no agents says nothing and is left out, or refused if the user drew it.
  for (auto& l : load_lines(grid, in.loads, options.depths))
    if (l.body_samples.size() >= 2) in.lines.push_back(std::move(l));
  for (std::size_t i = 0; i < options.lines.size(); ++i) {
    const std::string what = "line " + std::to_string(i + 1) + " of [[compare.line]]";
    in.lines.push_back(make_line(grid, options.lines[i][0], options.lines[i][1], what, "user"));
    if (in.lines.back().body_samples.size() < 2)
      file.root().table("compare").fail("line", what + " has fewer than 2 samples inside the agents (the rest is air or outside)");
  }
  in.far_distance = options.far_distance > 0 ? options.far_distance : 5 * grid.size[0];
  in.near = near_load(in.study.mesh, in.study.setup.loads, in.far_distance);
  std::vector<std::string> names;
  for (const auto& l : in.lines) names.push_back(l.name);
  report::check_gate_names(options, metric_names(options, names, grid.dim), file.root());
  file.reject_unknown_keys();
  return in;
}

namespace {

// Step 3: the agent model at every load step, each solved once (the last is the full load).
std::vector<agent_study::AgentState> run_agent(const agent_study::AgentStudy& study, const fs::path& dir,
                                               std::ostream& log) {
  fs::create_directories(dir / "agent");
  return agent_study::write_agent_outputs(study, dir / "agent", log);
}

/// Samples the sources that are given (not null) along `line` into `s`: first the agent and the
/// reference, then, once solved, the estimate (and staircase).
void sample_line(const agent::Grid& grid, const Line& line, const Sources& sources, ScopeSamples& s) {
  const int dim = grid.dim;
  for (int i : line.body_samples) {
    const Eigen::Vector3d p = line.point(i);
    for (const auto& [from, to] : kSources) {
      const GridFields* f = sources.*from;
      if (!f) continue;
      for (std::size_t k = 0; k < std::size(kFields); ++k) {
        const auto& field = kFields[k];
        if (!field.in(dim)) continue;
        auto& out = s[k].*to;
        if (!field.per_node)
          out.push_back(sample_cells(grid, f->stress, kStressSlots, field.slot, p));
        else if (field.slot >= 0)
          out.push_back(sample_nodes(grid, f->u, dim, field.slot, p));
        else
          for (int a = 0; a < dim; ++a) out.push_back(sample_nodes(grid, f->u, dim, a, p));
      }
    }
  }
}

// Step 7: the metrics of one scope; each error norm with the reference's own error beside it (and
// the staircase's own error beside a true-geometry reference). The zero model's relative L2 error
// is 1 (kZeroModelRelL2): report::finish flags the errors that are not below it.
void add_scope(CompareOutcome& out, const std::string& scope, const ScopeSamples& s, double mask, int dim) {
  for (std::size_t k = 0; k < std::size(kFields); ++k) {
    if (!kFields[k].in(dim)) continue;
    const Samples& v = s[k];
    const std::string name = scope + "." + kFields[k].name;
    const auto e = relative_errors(v.agent, v.reference);
    const auto r = relative_errors(v.estimate, v.reference);
    const auto st = v.staircase.empty() ? Errors{NAN, NAN} : relative_errors(v.staircase, v.reference);
    out.metrics.push_back({name + ".rel_l2", e.rel_l2, "||agent - FEM||_2 / ||FEM||_2", r.rel_l2, st.rel_l2});
    out.metrics.push_back({name + ".rel_max", e.rel_max, "max |agent - FEM| / max |FEM|", r.rel_max, st.rel_max});
  }
  for (std::size_t k = 0; k < std::size(kFields); ++k) {
    if (!kFields[k].ratios) continue;
    const std::string name = scope + "." + kFields[k].name;
    const auto r = ratios(s[k].agent, s[k].reference, mask);
    out.metrics.push_back({name + ".ratio_median_dev", std::abs(r.median - 1.0), "|median(agent / FEM) - 1|"});
    out.metrics.push_back({name + ".masked_fraction", double(r.masked_count) / double(std::max<std::size_t>(1, r.ratio.size())),
                           "share of entries where |FEM| < mask * max |FEM|"});
  }
}

/// The agents alone at the full load (docs/compare.md, "Agents against closed forms"): the study's
/// model with agent.closed_forms = "left_out", solved again; its fields on the grid.
GridFields agents_alone(const agent_study::AgentStudy& study) {
  auto k = study.coefficients;
  k.directional.closed_forms = agent::ClosedForms::LeftOut;
  auto model = agent_study::transfer_model(study, k, study.rules);
  return agent_on_grid(study.mesh.grid, agent_study::evaluate(study, model, 1.0));
}

/// Step 7b: each field metric's agents_only, the same error of the agents alone (`alone`) against
/// the reference, in every scope.
void add_agents_only(CompareOutcome& out, const AgentCompareInput& in, const GridFields& alone,
                     const GridFields& reference, double mask) {
  const auto& grid = in.study.mesh.grid;
  CompareOutcome apart;
  const Sources sources{&alone, &reference, &reference};  // (add_scope reads an estimate: its errors unused)
  add_field_scopes(apart, in, sources, mask);
  for (const auto& line : in.lines) {
    ScopeSamples s;
    sample_line(grid, line, sources, s);
    add_scope(apart, line.name, s, mask, grid.dim);
  }
  std::map<std::string, double> value;
  for (const auto& m : apart.metrics) value[m.name] = m.value;
  for (auto& m : out.metrics)
    if (const auto it = value.find(m.name); it != value.end()) m.agents_only = it->second;
}

/// Step 7c: every metric of a stress component the rule set does not model (agent::StressModel)
/// marked modelled = false, in every scope.
void mark_unmodelled(CompareOutcome& out, const agent::StressModel& model, int dim) {
  for (auto& m : out.metrics)
    if (!models_metric(m.name, model, dim)) m.modelled = false;
}

}  // namespace

bool agent_compare::models_metric(const std::string& name, const agent::StressModel& model, int dim) {
  for (const auto& f : kFields)
    if (f.in(dim) && !f.per_node && f.slot < kVonMises && !model.models(f.slot) &&
        name.find(std::string(".") + f.name + ".") != std::string::npos)
      return false;
  return true;
}

void agent_compare::add_field_scopes(CompareOutcome& out, const AgentCompareInput& in, const Sources& sources, double mask) {
  const auto& mesh = in.study.mesh;
  const auto& grid = mesh.grid;
  std::vector<char> body_cells(grid.count(), 0);
  for (std::size_t cell : mesh.cell_of_element) body_cells[cell] = 1;
  std::vector<char> body_nodes = compare::body_nodes(grid);
  std::vector<char> far_cells = body_cells, far_nodes = body_nodes;
  const auto cell_ids = agent_ids(grid), node_ids = body_node_ids(grid);  // box order on any layout
  for (std::size_t c = 0; c < far_cells.size(); ++c) far_cells[c] = far_cells[c] && !in.near.cells[c];
  for (std::size_t n = 0; n < far_nodes.size(); ++n) far_nodes[n] = far_nodes[n] && !in.near.nodes[n];
  for (const auto& [scope, cells, nodes] : {std::tuple{"body", &body_cells, &body_nodes},
                                            std::tuple{"far", &far_cells, &far_nodes}}) {
    ScopeSamples s;
    for (const auto& [from, to] : kSources) {
      const GridFields* f = sources.*from;
      if (!f) continue;
      const auto stress = select(f->stress, kStressSlots, cell_ids, *cells);
      const auto u = select(f->u, grid.dim, node_ids, *nodes);
      for (std::size_t k = 0; k < std::size(kFields); ++k) {
        const auto& field = kFields[k];
        if (!field.in(grid.dim)) continue;
        s[k].*to = !field.per_node ? component(stress, kStressSlots, field.slot)
                   : field.slot >= 0 ? component(u, grid.dim, field.slot) : u;
      }
    }
    add_scope(out, scope, s, mask, grid.dim);
  }
}

namespace {

/// Where the agent model's load went; warnings when it does not reach a rigid face.
void add_load_balance(CompareOutcome& out, const agent::Diagnostics& d, double min_share, std::size_t n_cells) {
  const double lost = d.applied - d.rigid_reaction - d.passed_out - d.dropped;
  out.metrics.push_back({"agent.equilibrium_dev", std::abs(d.rigid_reaction - d.applied) / d.applied,
                         "|rigid reaction - applied| / applied (agent)"});
  out.metrics.push_back({"agent.reaction_share", d.rigid_reaction / d.applied,
                         "rigid reaction / applied: the share of the load the agents carry to a rigid face"});
  out.metrics.push_back({"agent.lost_share", lost / d.applied,
                         "(applied - rigid reaction - passed out - dropped) / applied: load the transfer "
                         "coefficients lose"});
  out.metrics.push_back({"agent.reach_fraction", double(d.agents_generated) / double(n_cells),
                         "share of agents the load reaches"});
  for (const auto& w : agent_study::load_balance_warnings(d, min_share)) out.warnings.push_back("agent: " + w);
}

// Step 9: what the summary says beside the metrics.
nlohmann::json summary_header(const workbench::CaseFile& file, const AgentCompareInput& in,
                              const CompareOptions& options, const Reference& reference,
                              const agent::Diagnostics& d) {
  const auto& study = in.study;
  const auto& fem = reference.fem;
  nlohmann::json json;
  json["case"] = file.path().string();
  json["title"] = study.setup.title;
  json["model"] = "agent";
  const auto& setup = study.setup;
  json["geometry"] = {{"mesh", setup.mesh_file.string()}, {"mesh_parameters", setup.mesh_parameters},
                      {"mesh_unit_m", setup.mesh_unit}, {"agent_size", setup.agent_size},
                      {"dim", study.mesh.grid.dim}, {"young", setup.young}, {"poisson", setup.poisson},
                      {"thickness", setup.thickness}, {"rigid", setup.rigid_groups}, {"rollers", setup.roller_groups}};
  json["loads"] = nlohmann::json::array();
  for (const auto& l : setup.loads)
    json["loads"].push_back({{"group", l.group}, {"direction", l.direction_name()}, {"force", l.force}});
  json["agent"] = {{"rule_set", agent::rule_set_name(study.rules)},
                   {"readings", agent_study::names_of(study.readings)}, {"coefficients_used", nlohmann::json::array()},
                   {"agents", study.mesh.cell_of_element.size()}, {"agent_size", study.mesh.grid.size[0]},
                   {"applied", d.applied}, {"rigid_reaction", d.rigid_reaction}, {"passed_out", d.passed_out},
                   {"dropped", d.dropped}, {"lost", d.applied - d.rigid_reaction - d.passed_out - d.dropped},
                   {"agents_generated", d.agents_generated}, {"agent_updates", d.agent_updates},
                   {"packet_moves", d.packet_moves}};
  json["agent"]["threshold"] = {{"kind", agent::threshold_name(study.coefficients.threshold)},
                                {"gamma_in_effect", study.coefficients.gamma_for(agent_study::entering_load(study, 1.0))}};
  json["agent"]["not_in_effect"] = nlohmann::json::array();
  for (const auto& c : agent::kCoefficients) {  // every coefficient; those the rule set reads, named
    json["agent"]["coefficients"][c.name] = c.get(study.coefficients);
    if (c.used_by(study.rules)) json["agent"]["coefficients_used"].push_back(c.name);
    if (!c.acts_in(study.coefficients)) json["agent"]["not_in_effect"].push_back(c.name);  // the other threshold
    else if (c.acts) json["agent"]["threshold"]["coefficient"] = c.name;  // the threshold that acts
  }
  json["fields"] = nlohmann::json::array();  // the fields compared in this dimension (kFields), in its order
  for (const auto& f : kFields)
    if (f.in(study.mesh.grid.dim)) json["fields"].push_back(f.name);
  json["fem"] = {{"solver", fem.solver}, {"iterations", fem.iterations}, {"residual", fem.residual},
                 {"backward_error", fem.backward_error ? nlohmann::json(*fem.backward_error) : nlohmann::json()},
                 {"dofs", fem.n_dofs}, {"degree", fem.degree}, {"model", fem.model}};
  json["reference"] = level_json(reference);
  json["reference"].update({{"estimate", reference.estimate.describe()},
                            {"estimate_dofs", reference.estimate_dofs},
                            {"estimate_seconds", reference.estimate_seconds},
                            {"reference_error", "each error metric's reference_error: the same norm of the "
                                                "estimate level against the reference"}});
  if (reference.staircase_fields)
    json["reference"]["staircase"] = {
        {"dofs", reference.staircase_dofs},
        {"staircase_error", "each error metric's staircase_error: the same norm of FEM on the agents' own "
                            "(staircase) mesh at the reference's level against the reference"},
        {"agents_outside", reference.outside[0]},
        {"agent_nodes_outside", reference.outside[1]}};
  json["far_distance"] = in.far_distance;
  json["mask"] = options.mask;
  json["lines"] = lines_json(in.lines);
  return json;
}

/// The carry check in summary.json: each load, where it marches and whether the rule set carries it.
nlohmann::json carry_check_json(const std::vector<agent_study::LoadCarry>& carry, const agent_study::AgentStudy& study) {
  auto json = nlohmann::json::array();
  for (const auto& c : carry)
    json.push_back({{"load", c.load}, {"group", c.group}, {"rule_set", agent::rule_set_name(c.rules)},
                    {"march", agent::kDirectionNames[c.march]},
                    {"rigid_exit_area", c.exits.rigid}, {"free_exit_area", c.exits.free},
                    {"carries", !c.refused()}, {"said", c.describe(study)}});
  return json;
}

/// summary.txt's notes on the reference: its level and error estimate, the far field, the staircase.
std::vector<std::string> reference_notes(const AgentCompareInput& in, const Reference& reference) {
  std::vector<std::string> notes{
      "reference: " + reference.options.describe() + " (" + std::to_string(reference.fem.n_dofs) +
          " DoFs); its own error (column reference_error): the same norm of " + reference.estimate.describe() + " (" + std::to_string(reference.estimate_dofs) +
          " DoFs) against it",
      "far field: cells and nodes at least " + std::to_string(1e3 * in.far_distance).substr(0, 6) +
          " mm from every loaded face"};
  if (reference.staircase_fields)
    notes.push_back("the staircase's own error (column staircase_error): the same norm of FEM on the agents' mesh (" +
                    std::to_string(reference.staircase_dofs) + " DoFs, the reference's degree and refinement) against "
                    "the reference; " + std::to_string(reference.outside[0]) + " agents (wholly) and " +
                    std::to_string(reference.outside[1]) + " agent nodes lie outside the true geometry and take its "
                    "nearest element's stress / nearest node's displacement");
  return notes;
}

/// The input's warnings and the carry check's lines into `outcome` (and on rank 0's log); a load
/// the rule set cannot carry is named in outcome.refused. Returns the carry check.
std::vector<agent_study::LoadCarry> warn_before_the_run(const AgentCompareInput& in, CompareOutcome& outcome,
                                                         std::ostream& log) {
  auto carry = agent_study::carry_check(in.study);
  for (const auto& w : in.study.warnings) outcome.warnings.push_back("agent: " + w);  // the agent run says them
  for (const auto& w : in.warnings) {
    if (fem_reference::mpi_rank() == 0) log << "compare: warning: " << w << "\n" << std::flush;
    outcome.warnings.push_back(w);
  }
  for (const auto& c : carry) {
    const std::string line = c.describe(in.study);
    if (fem_reference::mpi_rank() == 0) log << "compare: carry check: " << line << "\n" << std::flush;
    if (c.refused()) outcome.refused.push_back(line);
  }
  return carry;
}

/// With [mesh] agent_size the agents' staircase as dir/agent_staircase.msh, for the FEM on it beside
/// the reference, written by rank 0 before any rank reads it; else an empty path.
fs::path write_staircase_file(const AgentCompareInput& in, const fs::path& dir) {
  if (!(in.study.setup.agent_size > 0)) return {};
  const fs::path staircase = dir / "agent_staircase.msh";
  fem_reference::mpi_collective([&] {
    if (fem_reference::mpi_rank() == 0) agent::write_staircase(in.study.mesh, staircase);
  });
  return staircase;
}

CompareOutcome run_agent_compare(const workbench::CaseFile& file, const CompareOptions& options, const fs::path& dir,
                                 std::ostream& log) {
  const auto start = std::chrono::steady_clock::now();
  // Under MPI every rank solves the FEM levels (their results are whole on every rank); rank 0
  // alone runs the agent model, compares and writes, each such step collective (a failure ends
  // every rank). One rank: every step runs here.
  using fem_reference::mpi_on_root;
  // 1. Figures 8-11 and the animation (compare/figures.py, matplotlib) are drawn beside the rest:
  // the script starts now, loading matplotlib while the case's mesh is read and the agent model
  // runs, draws the animation, which needs only the agents, while the FEM reference solves, and the
  // figures once the comparison's data is written (an error before then ends it).
  std::optional<report::BackgroundFigures> figures;
  mpi_on_root([&] {
    if (options.figures) figures.emplace(dir, options.figure_formats, log);
  });

  // 2. Read and check everything before running anything (every rank: bad input is one line).
  std::optional<AgentCompareInput> input;
  fem_reference::mpi_collective([&] { input.emplace(read_input(file, options)); });
  const auto& in = *input;
  const auto& grid = in.study.mesh.grid;
  if (figures) figures->title(in.study.setup.title.empty() ? file.path().stem().string() : in.study.setup.title);

  // 2b. The carry check: a load the rule set cannot carry to a rigid face is named, with the
  // reason, before anything runs (docs/compare.md); it fails the gate after the run.
  CompareOutcome outcome;
  const auto carry = warn_before_the_run(in, outcome, log);

  // 3. The agent model, every load step, on rank 0 beside the FEM reference (step 4), on a thread
  // of its own that then writes the animation's data and tells the script (figures is used by one
  // thread at a time: the main thread again only after agent_run.get()). The main thread alone
  // calls MPI; the two write the log through LineLogs, whole lines each.
  std::mutex log_lock;
  workbench::LineLog agent_log(log, log_lock), fem_log(log, log_lock);
  std::vector<agent_study::AgentState> states;
  GridFields alone_fields;  // with closed-form layers in the agents' fields, the agents alone
  double agent_seconds = 0;
  std::future<void> agent_run;
  if (fem_reference::mpi_rank() == 0)
    agent_run = std::async(std::launch::async, [&] {
      const auto t0 = std::chrono::steady_clock::now();
      states = run_agent(in.study, dir, agent_log);
      if (in.stress_model.closed_forms) alone_fields = agents_alone(in.study);
      agent_seconds = seconds_since(t0);
      write_steps_csv(dir / "steps.csv", in.study, states);
      report::write_text(dir / "lines.json", lines_json(in.lines).dump(1) + "\n");
      if (figures) figures->steps_ready();
    });

  // 4. The FEM reference (its output in dir/fem), on every rank; then the agent model's failure,
  // if it failed, ends every rank.
  auto t = std::chrono::steady_clock::now();
  // The agents voxelized in the run ([mesh] agent_size): their staircase as a file, for the FEM on it
  // beside the reference (the staircase's own error), written by rank 0 before any rank reads it.
  const fs::path staircase = write_staircase_file(in, dir);
  auto reference = solve_reference(in.problem, in.reference, in.study.mesh, dir, fem_log);
  double fem_seconds = seconds_since(t);
  mpi_on_root([&] { agent_run.get(); });

  // 5. Both models on the agent grid and along the lines, and the files the figures read: the
  // figures go on while the reference's own error is estimated.
  t = std::chrono::steady_clock::now();
  GridFields agent_fields;
  std::vector<ScopeSamples> samples(in.lines.size());
  mpi_on_root([&] {
    agent_fields = agent_on_grid(grid, states.back());
    for (std::size_t li = 0; li < in.lines.size(); ++li)
      sample_line(grid, in.lines[li], {&agent_fields, &reference.fields}, samples[li]);
    write_lines_csv(dir / "lines.csv", grid, in.lines, samples);
    write_field_files(dir, in, agent_fields, reference.fields, states.back(), options.mask);
    if (figures) figures->data_ready();
  });
  double compare_seconds = seconds_since(t);

  // 6. The reference's error estimate (and with the true geometry the staircase's own error), on
  // every rank.
  t = std::chrono::steady_clock::now();
  estimate_reference_error(reference, in.problem, in.study.mesh, log, staircase);
  if (!reference.stopped.empty()) outcome.warnings.push_back(reference.limits_judgement());
  fem_seconds += seconds_since(t);
  // 7-9 on rank 0.
  mpi_on_root([&] {
    const auto& agent_state = states.back();
    // 7. The metrics.
    t = std::chrono::steady_clock::now();
    const GridFields* staircase = reference.staircase_fields ? &*reference.staircase_fields : nullptr;
    for (std::size_t li = 0; li < in.lines.size(); ++li)
      sample_line(grid, in.lines[li], {nullptr, nullptr, &reference.estimate_fields, staircase}, samples[li]);
    add_field_scopes(outcome, in, {&agent_fields, &reference.fields, &reference.estimate_fields, staircase}, options.mask);
    for (std::size_t li = 0; li < in.lines.size(); ++li)
      add_scope(outcome, in.lines[li].name, samples[li], options.mask, grid.dim);
    if (in.stress_model.closed_forms) add_agents_only(outcome, in, alone_fields, reference.fields, options.mask);
    mark_unmodelled(outcome, in.stress_model, grid.dim);
    add_load_balance(outcome, agent_state.diagnostics, options.min_reaction_share, grid.agent_count());
    outcome.metrics.push_back({"fem.equilibrium_dev", report::fem_equilibrium_dev(reference.fem),
                               "|reactions + applied| / |applied| (FEM)"});
    compare_seconds += seconds_since(t);
    outcome.metrics.push_back({"time.agent_s", agent_seconds, "agent model, all load steps with output [s]"});
    outcome.metrics.push_back({"time.fem_s", fem_seconds, "FEM reference, both levels, with output [s]"});
    outcome.metrics.push_back({"time.compare_s", compare_seconds, "comparison and its output [s]"});

    // 8. The figures: what is left of them once the rest is done.
    t = std::chrono::steady_clock::now();
    if (figures) figures->drawn();
    outcome.metrics.push_back({"time.figures_wait_s", seconds_since(t),
                               "waiting for the figures after the rest (they are drawn beside the FEM reference) [s]"});
    outcome.metrics.push_back({"time.total_s", seconds_since(start), "the whole study [s]"});

    // 9. The gate, summary.json / summary.txt / junit.xml, then report.html (rendered by the figures' process).
    outcome.fields = compared_fields(in, agent_fields, reference.fields, agent_state, options.mask, samples);
    auto json = summary_header(file, in, options, reference, agent_state.diagnostics);
    json["carry_check"] = carry_check_json(carry, in.study);
    for (const auto& r : outcome.refused) outcome.warnings.push_back("agent: carry check: " + r);
    report::finish(dir, file.path(), std::move(json), options.gate, reference_notes(in, reference), outcome, log,
                   options.better_than_zero, figures ? &*figures : nullptr);
  });
  return outcome;
}

}  // namespace

std::vector<std::string> check_compare(const workbench::CaseFile& file) {
  const auto options = read_compare_options(file.root());
  std::vector<std::string> warnings;
  fem_reference::mpi_collective([&] {
    if (options.model == "pbd") return check_pbd_compare(file, options);
    const auto in = read_input(file, options);
    warnings = in.study.warnings;
    warnings.insert(warnings.end(), in.warnings.begin(), in.warnings.end());
  });
  return warnings;
}

CompareOutcome run_compare(const workbench::CaseFile& file, const fs::path& dir, std::ostream& log) {
  const auto options = read_compare_options(file.root());
  if (options.model == "pbd" && fem_reference::mpi_size() > 1)  // every rank says so: printed once
    throw fem_reference::CollectiveError(file.path().string() + ": compare.model = \"pbd\" runs on one rank (its FEM "
                                         "strip is small): run it without mpirun");
  return options.model == "pbd" ? run_pbd_compare(file, options, dir, log) : run_agent_compare(file, options, dir, log);
}

}  // namespace compare

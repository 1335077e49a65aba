// The agent comparison (docs/compare.md): the agent method against the converged FEM reference
// on the same body, in named steps: read, run the agent model, solve the reference, sample,
// score, write, draw, summarise.
#include <compare/compare_study.h>
#include <compare/pbd_compare.h>
#include <compare/reference.h>

#include "report.h"

#include <agent_study.h>
#include <fem_reference/fem_case.h>
#include <workbench/csv_file.h>
#include <workbench/error.h>
#include <workbench/vtk_output.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <future>
#include <cmath>
#include <optional>
#include <ostream>

namespace compare {

namespace fs = std::filesystem;
using workbench::Error;

CompareOptions read_compare_options(const workbench::CaseTable& root) {
  const auto t = root.table("compare");
  CompareOptions o;
  o.model = t.text("model", o.model, {"agent", "pbd"});
  if (o.model == "agent") {  // the PBD comparison has no sample lines nor ratios: its case rejects these keys
    o.depths = t.numbers("depths", o.depths, workbench::Range::open(0.0, 1.0));
    o.mask = t.number("mask", o.mask, workbench::Range{0.0, 1.0, false, true});
    const auto r = t.table("reference");
    o.reference.degree = r.integer("degree", o.reference.degree, 1, 2);
    if (r.has("refine")) o.reference.refine = r.integer("refine", std::nullopt, 0, 4);
    if (r.has("mesh")) {
      o.reference.mesh = r.path("mesh", std::nullopt);
      if (!fs::is_regular_file(o.reference.mesh)) r.fail("mesh", o.reference.mesh.string() + ": no such mesh file");
    }
    t.refuse_renamed("far_distance_mm", "far_distance", "in metres: far_distance_mm / 1000");
    o.far_distance = t.number("far_distance", o.far_distance, workbench::Range::non_negative());
    o.min_reaction_share = t.number("min_reaction_share", o.min_reaction_share, workbench::Range::closed(0.0, 1.0));
    for (const auto& line : t.tables("line")) {
      std::array<Eigen::Vector3d, 2> ends{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
      const char* keys[] = {"from", "to"};
      for (int e = 0; e < 2; ++e) {
        const auto p = line.numbers(keys[e], std::nullopt);
        if (p.size() < 2 || p.size() > 3) line.fail(keys[e], "a point is 2 or 3 coordinates [m]");
        for (std::size_t a = 0; a < p.size(); ++a) ends[e][a] = p[a];
      }
      if ((ends[1] - ends[0]).norm() == 0) line.fail("to", "the line's ends are the same point");
      o.lines.push_back(ends);
    }
  }
  o.gate = t.number_map("gate");
  for (const auto& [name, limit] : o.gate)
    if (!(limit >= 0) || !std::isfinite(limit)) t.fail("gate." + name, "a limit must be a finite number >= 0");
  o.figures = t.flag("figures", true);
  o.figure_formats = t.texts("figure_formats", o.figure_formats);
  if (o.figure_formats.empty()) t.fail("figure_formats", "name at least one format (\"png\", \"pdf\")");
  for (const auto& f : o.figure_formats)
    if (f != "png" && f != "pdf") t.fail("figure_formats", "unknown format \"" + f + "\" (\"png\" or \"pdf\")");
  return o;
}

namespace {

const char* kFields[] = {"sigma_x", "sigma_y", "displacement"};

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

std::vector<std::string> agent_metric_names(const std::vector<std::string>& line_names) {
  std::vector<std::string> scopes{"body", "far"};
  scopes.insert(scopes.end(), line_names.begin(), line_names.end());
  std::vector<std::string> names;
  for (const auto& s : scopes) {
    for (const char* f : kFields)
      for (const char* n : {"rel_l2", "rel_max"}) names.push_back(s + "." + f + "." + n);
    for (const char* f : {"sigma_x", "sigma_y"}) {
      names.push_back(s + "." + f + ".ratio_median_dev");
      names.push_back(s + "." + f + ".masked_fraction");
    }
  }
  for (const char* n : {"agent.equilibrium_dev", "agent.lost_share", "agent.reaction_share", "fem.equilibrium_dev",
                        "agent.reach_fraction", "time.agent_s", "time.fem_s", "time.compare_s", "time.figures_wait_s",
                        "time.total_s"})
    names.push_back(n);
  return names;
}

}  // namespace

std::vector<std::string> metric_names(const CompareOptions& options, const std::vector<std::string>& line_names) {
  return options.model == "pbd" ? pbd_metric_names() : agent_metric_names(line_names);
}

namespace {

// Step 1: the inputs.
struct AgentCompareInput {
  agent_study::AgentStudy study;
  fem_reference::FemProblem problem;
  std::vector<LoadFrame> loads;
  std::vector<Line> lines;  ///< each load's lines, then the user's
  NearLoad near;            ///< cells and nodes left out of the far field
  double far_distance = 0;  ///< [m]
  ReferenceOptions reference;  ///< resolved for the mesh's dimension
};

AgentCompareInput read_input(const workbench::CaseFile& file, const CompareOptions& options) {
  AgentCompareInput in{agent_study::load_agent_study(file), fem_reference::problem_from_case(file), {}, {}, {}, 0, {}};
  const auto& grid = in.study.mesh.grid;
  in.reference = options.reference.resolved(grid.dim);
  in.loads = load_frames(in.study.mesh, in.study.setup.loads);
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
  report::check_gate_names(options, metric_names(options, names), file.root());
  file.reject_unknown_keys();
  return in;
}

// Step 2: the agent model at every load step, each solved once (the last is the full load).
std::vector<agent_study::AgentState> run_agent(const agent_study::AgentStudy& study, const fs::path& dir,
                                               std::ostream& log) {
  fs::create_directories(dir / "agent");
  return agent_study::write_agent_outputs(study, dir / "agent", log);
}

// Steps 5 and 7: what a comparison samples, from where.
/// The fields compared: the agent model, the reference, the reference's second level (for its own
/// error) and, beside a true-geometry reference, FEM on the agents' staircase mesh (else null).
struct Sources {
  const GridFields* agent = nullptr;
  const GridFields* reference = nullptr;
  const GridFields* estimate = nullptr;
  const GridFields* staircase = nullptr;
};
/// One field's values in a scope, per source (empty where the source is not sampled).
struct Samples {
  std::vector<double> agent, reference, estimate, staircase;
};
/// A scope's values of each field of kFields: sigma_x, sigma_y per agent, u per node component.
struct ScopeSamples {
  Samples sigma_x, sigma_y, u;
};
/// Each source with where its samples go.
const std::pair<const GridFields* Sources::*, std::vector<double> Samples::*> kSources[] = {
    {&Sources::agent, &Samples::agent},
    {&Sources::reference, &Samples::reference},
    {&Sources::estimate, &Samples::estimate},
    {&Sources::staircase, &Samples::staircase}};

/// Samples the sources that are given (not null) along `line` into `s`: first the agent and the
/// reference, then, once solved, the estimate (and staircase).
void sample_line(const agent::Grid& grid, const Line& line, const Sources& sources, ScopeSamples& s) {
  for (int i : line.body_samples) {
    const Eigen::Vector3d p = line.point(i);
    for (const auto& [from, to] : kSources) {
      const GridFields* f = sources.*from;
      if (!f) continue;
      (s.sigma_x.*to).push_back(sample_cells(grid, f->sigma, 2, 0, p));
      (s.sigma_y.*to).push_back(sample_cells(grid, f->sigma, 2, 1, p));
      for (int a = 0; a < 2; ++a) (s.u.*to).push_back(sample_nodes(grid, f->u, grid.dim, a, p));
    }
  }
}

// Step 7: the metrics of one scope; each error norm with the reference's own error beside it (and
// the staircase's own error beside a true-geometry reference).
void add_scope(CompareOutcome& out, const std::string& scope, const ScopeSamples& s, double mask) {
  const Samples* fields[3] = {&s.sigma_x, &s.sigma_y, &s.u};  // kFields
  for (int f = 0; f < 3; ++f) {
    const Samples& v = *fields[f];
    const auto e = relative_errors(v.agent, v.reference);
    const auto r = relative_errors(v.estimate, v.reference);
    const auto st = v.staircase.empty() ? Errors{NAN, NAN} : relative_errors(v.staircase, v.reference);
    out.metrics.push_back(
        {scope + "." + kFields[f] + ".rel_l2", e.rel_l2, "||agent - FEM||_2 / ||FEM||_2", r.rel_l2, st.rel_l2});
    out.metrics.push_back(
        {scope + "." + kFields[f] + ".rel_max", e.rel_max, "max |agent - FEM| / max |FEM|", r.rel_max, st.rel_max});
  }
  for (int f = 0; f < 2; ++f) {
    const auto r = ratios(fields[f]->agent, fields[f]->reference, mask);
    out.metrics.push_back({scope + "." + kFields[f] + ".ratio_median_dev", std::abs(r.median - 1.0),
                           "|median(agent / FEM) - 1|"});
    out.metrics.push_back({scope + "." + kFields[f] + ".masked_fraction",
                           double(r.masked_count) / double(std::max<std::size_t>(1, r.ratio.size())),
                           "share of entries where |FEM| < mask * max |FEM|"});
  }
}

/// The body's cells and nodes (box order), and the far field's: air counts in neither.
void add_field_scopes(CompareOutcome& out, const AgentCompareInput& in, const Sources& sources, double mask) {
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
      const auto sigma = select(f->sigma, 2, cell_ids, *cells);
      s.sigma_x.*to = component(sigma, 2, 0);
      s.sigma_y.*to = component(sigma, 2, 1);
      s.u.*to = select(f->u, grid.dim, node_ids, *nodes);
    }
    add_scope(out, scope, s, mask);
  }
}

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

// Step 5: the files (steps.csv in step 2).
void write_lines_csv(const fs::path& file, const agent::Grid& grid, const std::vector<Line>& lines,
                     const std::vector<ScopeSamples>& samples) {
  const int dim = grid.dim;
  auto csv = open_csv(file);
  csv << "model,line,arc_length [m],x [m],y [m]" << (dim == 3 ? ",z [m]" : "") << ",sigma_x [Pa],sigma_y [Pa],u_x [m],u_y [m]\n";
  for (std::size_t li = 0; li < lines.size(); ++li)
    for (int m = 0; m < 2; ++m)
      for (std::size_t i = 0; i < lines[li].body_samples.size(); ++i) {  // the samples in the body only
        const Eigen::Vector3d p = lines[li].point(lines[li].body_samples[i]);
        const auto& s = samples[li];
        csv << (m == 0 ? "agent" : "fem") << ',' << lines[li].name << ',' << (p - lines[li].from).norm();
        for (int a = 0; a < dim; ++a) csv << ',' << p[a];
        const auto& to = kSources[m].second;  // the agent (m = 0) or the reference
        csv << ',' << (s.sigma_x.*to)[i] << ',' << (s.sigma_y.*to)[i] << ',' << (s.u.*to)[2 * i] << ','
            << (s.u.*to)[2 * i + 1] << '\n';
      }
  csv.close();  // complete on disk before figures.py reads it
}

void write_field_files(const fs::path& dir, const AgentCompareInput& in, const GridFields& agent,
                       const GridFields& fem, const agent_study::AgentState& state, double mask) {
  const auto& study = in.study;
  const auto& grid = study.mesh.grid;
  const int dim = grid.dim;
  const auto mesh = agent_study::output_mesh(study);
  const auto rx = ratios(component(agent.sigma, 2, 0), component(fem.sigma, 2, 0), mask);
  const auto ry = ratios(component(agent.sigma, 2, 1), component(fem.sigma, 2, 1), mask);
  std::vector<workbench::Field> cells;
  for (const char* n : {"agent_sigma_x [Pa]", "agent_sigma_y [Pa]", "fem_sigma_x [Pa]", "fem_sigma_y [Pa]",
                        "diff_sigma_x [Pa]", "diff_sigma_y [Pa]", "ratio_sigma_x [-]", "ratio_sigma_y [-]",
                        "ratio_masked_x [-]", "ratio_masked_y [-]", "generation [-]", "far [-]"})
    cells.push_back({n, 1, {}, {}, {}});
  for (std::size_t cell : study.mesh.cell_of_element) {
    const double v[] = {agent.sigma[2 * cell], agent.sigma[2 * cell + 1], fem.sigma[2 * cell], fem.sigma[2 * cell + 1],
                        agent.sigma[2 * cell] - fem.sigma[2 * cell], agent.sigma[2 * cell + 1] - fem.sigma[2 * cell + 1],
                        rx.ratio[cell], ry.ratio[cell], double(rx.masked[cell]), double(ry.masked[cell]),
                        double(state.generation[cell]), double(!in.near.cells[cell])};
    for (std::size_t f = 0; f < cells.size(); ++f) cells[f].values.push_back(v[f]);
  }
  for (std::size_t cell : study.mesh.cell_of_element) {  // masked ratios: NaN, blanked by ParaView
    cells[6].undefined.push_back(rx.masked[cell]);
    cells[7].undefined.push_back(ry.masked[cell]);
  }
  const std::vector<std::string> xyz{"x", "y", "z"};
  std::vector<workbench::Field> points{
      {"agent_u [m]", 3, {}, xyz, {}}, {"fem_u [m]", 3, {}, xyz, {}}, {"diff_u [m]", 3, {}, xyz, {}}};
  for (std::size_t n = 0; n < grid.node_count(); ++n)
    for (int a = 0; a < 3; ++a) {
      const double ua = a < dim ? agent.u[n * dim + a] : 0.0, uf = a < dim ? fem.u[n * dim + a] : 0.0;
      points[0].values.push_back(ua);
      points[1].values.push_back(uf);
      points[2].values.push_back(ua - uf);
    }
  workbench::write_vtu(dir / "compare.vtu", mesh, points, cells);

  // A masked ratio means nothing: an empty field on purpose (workbench::CsvFile, docs/compare.md); NaN in compare.vtu.
  auto ratio_field = [](const Ratios& r, std::size_t cell) {
    return r.masked[cell] ? std::nullopt : std::optional<double>(r.ratio[cell] + 0.0);  // + 0.0: no "-0"
  };
  auto cells_csv = open_csv(dir / "cells.csv");
  cells_csv << "cell,x [m],y [m]" << (dim == 3 ? ",z [m]" : "")
            << ",generation,agent_sigma_x [Pa],agent_sigma_y [Pa],fem_sigma_x [Pa],fem_sigma_y [Pa],ratio_sigma_x [-],"
               "ratio_sigma_y [-],masked_x,masked_y,far\n";
  for (std::size_t e = 0; e < study.mesh.cell_of_element.size(); ++e) {
    const std::size_t cell = study.mesh.cell_of_element[e];
    const Eigen::Vector3d c = grid.centre(cell);
    cells_csv << e;
    for (int a = 0; a < dim; ++a) cells_csv << ',' << c[a];
    cells_csv << ',' << state.generation[cell] << ',' << agent.sigma[2 * cell] << ',' << agent.sigma[2 * cell + 1] << ','
              << fem.sigma[2 * cell] << ',' << fem.sigma[2 * cell + 1] << ',' << ratio_field(rx, cell) << ',' << ratio_field(ry, cell)
              << ',' << int(rx.masked[cell]) << ',' << int(ry.masked[cell]) << ',' << int(!in.near.cells[cell]) << '\n';
  }
  auto nodes_csv = open_csv(dir / "nodes.csv");
  nodes_csv << "i,j" << (dim == 3 ? ",k" : "") << ",x [m],y [m]" << (dim == 3 ? ",z [m]" : "")
            << ",agent_u_x [m],agent_u_y [m]" << (dim == 3 ? ",agent_u_z [m]" : "") << ",fem_u_x [m],fem_u_y [m]"
            << (dim == 3 ? ",fem_u_z [m]" : "") << "\n";
  for (std::size_t n : compare::body_node_ids(grid)) {  // air has no nodes; box order on any layout
    const auto c = grid.node_coords(n);
    nodes_csv << c[0] << ',' << c[1];
    if (dim == 3) nodes_csv << ',' << c[2];
    for (int a = 0; a < dim; ++a) nodes_csv << ',' << mesh.points[3 * n + a];
    for (int a = 0; a < dim; ++a) nodes_csv << ',' << agent.u[n * dim + a];
    for (int a = 0; a < dim; ++a) nodes_csv << ',' << fem.u[n * dim + a];
    nodes_csv << '\n';
  }
  cells_csv.close();
  nodes_csv.close();
}

/// The agent's sigma per cell at every load step, with the cell's centre (the animation's data,
/// drawn before the other files exist).
void write_steps_csv(const fs::path& file, const agent_study::AgentStudy& study,
                     const std::vector<agent_study::AgentState>& states) {
  const auto& grid = study.mesh.grid;
  const int dim = grid.dim;
  auto csv = open_csv(file);
  csv << "step,load [N],cell,x [m],y [m]" << (dim == 3 ? ",z [m]" : "") << ",generation,sigma_x [Pa],sigma_y [Pa]\n";
  for (std::size_t k = 0; k < states.size(); ++k) {
    const auto& s = states[k];
    for (std::size_t e = 0; e < study.mesh.cell_of_element.size(); ++e) {
      const std::size_t cell = study.mesh.cell_of_element[e];
      const Eigen::Vector3d c = grid.centre(cell);
      csv << k + 1 << ',' << s.diagnostics.applied << ',' << e;
      for (int a = 0; a < dim; ++a) csv << ',' << c[a];
      csv << ',' << s.generation[cell] << ',' << s.stress[cell * dim] << ',' << s.stress[cell * dim + 1] << '\n';
    }
  }
  csv.close();
}

/// The sample lines as lines.json (for the figures) and summary.json list them.
nlohmann::json lines_json(const std::vector<Line>& lines) {
  auto json = nlohmann::json::array();
  for (const auto& l : lines)
    json.push_back({{"name", l.name}, {"description", l.description}, {"kind", l.kind},
                    {"from", {l.from[0], l.from[1], l.from[2]}}, {"to", {l.to[0], l.to[1], l.to[2]}}});
  return json;
}

// Step 9: what the summary says beside the metrics.
nlohmann::json summary_header(const workbench::CaseFile& file, const AgentCompareInput& in,
                              const CompareOptions& options, const Reference& reference,
                              const agent::Diagnostics& d) {
  const auto& study = in.study;
  const auto& k = study.coefficients;
  const auto& fem = reference.fem;
  nlohmann::json json;
  json["case"] = file.path().string();
  json["title"] = study.setup.title;
  json["model"] = "agent";
  json["agent"] = {{"rule_set", agent::rule_set_name(study.rules)},
                   {"readings", agent_study::names_of(study.readings)},
                   {"agents", study.mesh.cell_of_element.size()}, {"agent_size", study.mesh.grid.size[0]},
                   {"applied", d.applied}, {"rigid_reaction", d.rigid_reaction}, {"passed_out", d.passed_out},
                   {"dropped", d.dropped}, {"lost", d.applied - d.rigid_reaction - d.passed_out - d.dropped},
                   {"agents_generated", d.agents_generated}, {"agent_updates", d.agent_updates},
                   {"packet_moves", d.packet_moves}};
  for (const auto& [name, value] : agent_study::coefficient_values(study.coefficients))
    json["agent"]["coefficients"][name] = value;
  json["fem"] = {{"solver", fem.solver}, {"iterations", fem.iterations}, {"residual", fem.residual},
                 {"backward_error", fem.backward_error ? nlohmann::json(*fem.backward_error) : nlohmann::json()},
                 {"dofs", fem.n_dofs}, {"degree", fem.degree}, {"model", fem.model}};
  json["reference"] = {{"description", in.reference.describe()},
                       {"degree", in.reference.degree},
                       {"refine", in.reference.refine},
                       {"dofs", fem.n_dofs},
                       {"estimate", reference.estimate.describe()},
                       {"estimate_dofs", reference.estimate_dofs},
                       {"estimate_seconds", reference.estimate_seconds},
                       {"reference_error", "each error metric's reference_error: the same norm of the estimate "
                                           "level against the reference"}};
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

CompareOutcome run_agent_compare(const workbench::CaseFile& file, const CompareOptions& options, const fs::path& dir,
                                 std::ostream& log) {
  const auto start = std::chrono::steady_clock::now();
  // 1. Read and check everything before running anything.
  const auto in = read_input(file, options);
  const auto& grid = in.study.mesh.grid;

  // 2. The agent model, every load step.
  auto t = std::chrono::steady_clock::now();
  const auto states = run_agent(in.study, dir, log);
  const auto& agent_state = states.back();
  const double agent_seconds = seconds_since(t);

  // 3. Figures 8-11 and the animation (compare/figures.py, matplotlib) are drawn beside the rest:
  // the animation, which needs only the agents, while the FEM reference solves. Its data is
  // written on a thread beside the reference too, which then tells the script (figures is used
  // by one thread at a time: the main thread again only after animation_data.get()).
  const std::string title = in.study.setup.title.empty() ? file.path().stem().string() : in.study.setup.title;
  std::optional<report::BackgroundFigures> figures;
  if (options.figures) figures.emplace(dir, title, options.figure_formats, log);
  auto animation_data = std::async(std::launch::async, [&] {
    write_steps_csv(dir / "steps.csv", in.study, states);
    report::write_text(dir / "lines.json", lines_json(in.lines).dump(1) + "\n");
    if (figures) figures->steps_ready();
  });

  // 4. The FEM reference (its output in dir/fem).
  t = std::chrono::steady_clock::now();
  auto reference = solve_reference(in.problem, in.reference, in.study.mesh, dir, log);
  double fem_seconds = seconds_since(t);

  // 5. Both models on the agent grid and along the lines, and the files the figures read: the
  // figures go on while the reference's own error is estimated.
  t = std::chrono::steady_clock::now();
  const auto agent_fields = agent_on_grid(grid, agent_state);
  std::vector<ScopeSamples> samples(in.lines.size());
  for (std::size_t li = 0; li < in.lines.size(); ++li)
    sample_line(grid, in.lines[li], {&agent_fields, &reference.fields}, samples[li]);
  write_lines_csv(dir / "lines.csv", grid, in.lines, samples);
  write_field_files(dir, in, agent_fields, reference.fields, agent_state, options.mask);
  animation_data.get();
  if (figures) figures->data_ready();
  double compare_seconds = seconds_since(t);

  // 6. The reference's error estimate (and with the true geometry the staircase's own error).
  t = std::chrono::steady_clock::now();
  estimate_reference_error(reference, in.problem, in.reference, in.study.mesh, log);
  fem_seconds += seconds_since(t);

  // 7. The metrics.
  t = std::chrono::steady_clock::now();
  const GridFields* staircase = reference.staircase_fields ? &*reference.staircase_fields : nullptr;
  for (std::size_t li = 0; li < in.lines.size(); ++li)
    sample_line(grid, in.lines[li], {nullptr, nullptr, &reference.estimate_fields, staircase}, samples[li]);
  CompareOutcome outcome;
  add_field_scopes(outcome, in, {&agent_fields, &reference.fields, &reference.estimate_fields, staircase}, options.mask);
  for (std::size_t li = 0; li < in.lines.size(); ++li) add_scope(outcome, in.lines[li].name, samples[li], options.mask);
  add_load_balance(outcome, agent_state.diagnostics, options.min_reaction_share, grid.agent_count());
  outcome.metrics.push_back({"fem.equilibrium_dev", report::fem_equilibrium_dev(reference.fem),
                             "|reactions + applied| / |applied| (FEM)"});
  compare_seconds += seconds_since(t);
  outcome.metrics.push_back({"time.agent_s", agent_seconds, "agent model, all load steps with output [s]"});
  outcome.metrics.push_back({"time.fem_s", fem_seconds, "FEM reference, both levels, with output [s]"});
  outcome.metrics.push_back({"time.compare_s", compare_seconds, "comparison and its output [s]"});

  // 8. The figures: what is left of them once the rest is done.
  t = std::chrono::steady_clock::now();
  if (figures) figures->finish();
  outcome.metrics.push_back({"time.figures_wait_s", seconds_since(t),
                             "waiting for the figures after the rest (they are drawn beside the FEM reference) [s]"});
  outcome.metrics.push_back({"time.total_s", seconds_since(start), "the whole study [s]"});

  // 9. The gate, summary.json / summary.txt / junit.xml.
  auto json = summary_header(file, in, options, reference, agent_state.diagnostics);
  std::vector<std::string> notes{
      "reference: " + in.reference.describe() + " (" + std::to_string(reference.fem.n_dofs) +
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
  report::finish(dir, file.path(), std::move(json), options.gate, notes, outcome, log);
  return outcome;
}

}  // namespace

CompareOutcome run_compare(const workbench::CaseFile& file, const fs::path& dir, std::ostream& log) {
  const auto options = read_compare_options(file.root());
  return options.model == "pbd" ? run_pbd_compare(file, options, dir, log) : run_agent_compare(file, options, dir, log);
}

}  // namespace compare

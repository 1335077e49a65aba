#include <compare/compare_study.h>
#include <compare/reference.h>

#include "report.h"

#include <agent_study.h>
#include <fem_reference/fem.h>
#include <workbench/error.h>
#include <workbench/vtk_output.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>

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
  }
  o.gate = t.number_map("gate");
  for (const auto& [name, limit] : o.gate)
    if (!(limit >= 0) || !std::isfinite(limit)) t.fail("gate." + name, "a limit must be a finite number >= 0");
  o.figures = t.flag("figures", true);
  return o;
}

namespace {

const char* kFields[] = {"sigma_x", "sigma_y", "displacement"};

std::string line_name(double depth) {
  std::ostringstream s;
  s << "depth_" << depth;
  return s.str();
}

using report::open_out;
using report::seconds_since;

}  // namespace

GridFields fem_on_grid(const agent_study::AgentStudy& study, const fem_reference::FemResult& fem,
                       const std::string& case_name) {
  const auto& grid = study.mesh.grid;
  const int dim = grid.dim;
  if (fem.cell_count() != study.mesh.cell_of_element.size() || fem.dim != dim)
    throw Error(case_name + ": the FEM and agent meshes differ (" + std::to_string(fem.cell_count()) + " against " +
                std::to_string(study.mesh.cell_of_element.size()) + " cells)");
  GridFields out;
  out.sigma.assign(grid.count() * 2, 0.0);
  for (std::size_t e = 0; e < fem.cell_count(); ++e) {
    const std::size_t cell = study.mesh.cell_of_element[e];
    const Eigen::Vector3d c = grid.centre(cell);
    for (int a = 0; a < dim; ++a)
      if (std::abs(c[a] - fem.cell_centres[3 * e + a]) > 1e-6 * grid.size[a])
        throw Error(case_name + ": FEM element " + std::to_string(e) + " is not where agent " + std::to_string(cell) +
                    " is (meshes generated differently)");
    out.sigma[2 * cell] = fem.sigma_x[e];
    out.sigma[2 * cell + 1] = fem.sigma_y[e];
  }
  out.u.assign(grid.node_count() * dim, 0.0);
  std::vector<char> found(grid.node_count(), 0);
  for (std::size_t n = 0; n < fem.node_count(); ++n) {
    int p[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a) p[a] = int(std::lround((fem.node_points[3 * n + a] - grid.origin[a]) / grid.size[a]));
    const std::size_t node = grid.node_index(p[0], p[1], p[2]);
    for (int a = 0; a < dim; ++a) out.u[node * dim + a] = fem.node_displacement[n * dim + a];
    found[node] = 1;
  }
  // Every corner of an agent needs a FEM node (nodes of the box that touch only air have none).
  for (std::size_t cell = 0; cell < grid.count(); ++cell) {
    if (grid.is_air(cell)) continue;
    const auto c = grid.coords(cell);
    for (int corner = 0; corner < (1 << dim); ++corner)
      if (!found[grid.node_index(c[0] + (corner & 1), c[1] + ((corner >> 1) & 1), c[2] + ((corner >> 2) & 1))])
        throw Error(case_name + ": FEM nodes do not cover the agent grid's nodes");
  }
  return out;
}

GridFields agent_on_grid(const agent_study::AgentStudy& study, const agent_study::AgentState& state) {
  const auto& grid = study.mesh.grid;
  GridFields out;
  out.sigma.resize(grid.count() * 2);
  for (std::size_t cell = 0; cell < grid.count(); ++cell) {
    out.sigma[2 * cell] = state.stress[cell * grid.dim];
    out.sigma[2 * cell + 1] = state.stress[cell * grid.dim + 1];
  }
  out.u = state.displacement;
  return out;
}

namespace {

std::vector<std::string> agent_metric_names(const std::vector<double>& depths) {
  std::vector<std::string> scopes{"body", "vertical"};
  for (double d : depths) scopes.push_back(line_name(d));
  std::vector<std::string> names;
  for (const auto& s : scopes) {
    for (const char* f : kFields)
      for (const char* n : {"rel_l2", "rel_max"}) names.push_back(s + "." + f + "." + n);
    for (const char* f : {"sigma_x", "sigma_y"}) {
      names.push_back(s + "." + f + ".ratio_median_dev");
      names.push_back(s + "." + f + ".masked_fraction");
    }
  }
  for (const char* n : {"agent.equilibrium_dev", "fem.equilibrium_dev", "agent.reach_fraction", "time.agent_s",
                        "time.fem_s", "time.compare_s", "time.figures_s", "time.total_s"})
    names.push_back(n);
  return names;
}

}  // namespace

std::vector<std::string> metric_names(const CompareOptions& options) {
  return options.model == "pbd" ? pbd_metric_names() : agent_metric_names(options.depths);
}

namespace {

CompareOutcome run_agent_compare(const workbench::CaseFile& file, const CompareOptions& options, const fs::path& dir,
                                 std::ostream& log) {
  const auto start = std::chrono::steady_clock::now();
  const auto root = file.root();
  auto study = agent_study::load_agent_study(file);
  auto problem = fem_reference::problem_from_case(file);
  report::check_gate_names(options, metric_names(options), root);
  file.reject_unknown_keys();
  const auto& grid = study.mesh.grid;
  const int dim = grid.dim;

  // The agent model: every load step (VTU series) and the full load.
  auto t = std::chrono::steady_clock::now();
  fs::create_directories(dir / "agent");
  agent_study::write_agent_outputs(study, dir / "agent", log);
  agent::LoadTransfer model(grid, {study.setup.young, study.setup.poisson}, study.coefficients, study.rules);
  const auto agent = agent_study::evaluate(study, model, 1.0);
  const double agent_seconds = seconds_since(t);

  // The FEM reference on the same mesh.
  double fem_seconds = 0;
  const auto fem = report::run_fem(problem, dir, log, fem_seconds);
  t = std::chrono::steady_clock::now();

  const std::size_t n_cells = grid.agent_count();
  const auto fem_fields = fem_on_grid(study, fem, file.path().string());
  const auto agent_fields = agent_on_grid(study, agent);
  const auto& fem_sigma = fem_fields.sigma;
  const auto& agent_sigma = agent_fields.sigma;
  const auto& fem_u = fem_fields.u;

  CompareOutcome outcome;
  auto add = [&](const std::string& name, double value, const std::string& meaning) {
    outcome.metrics.push_back({name, value, meaning});
  };
  auto component = [](const std::vector<double>& v, int comps, int c) {
    std::vector<double> out(v.size() / comps);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = v[i * comps + c];
    return out;
  };
  auto add_scope = [&](const std::string& scope, const std::vector<double>& a_sx, const std::vector<double>& f_sx,
                       const std::vector<double>& a_sy, const std::vector<double>& f_sy,
                       const std::vector<double>& a_u, const std::vector<double>& f_u) {
    const std::vector<const std::vector<double>*> models{&a_sx, &a_sy, &a_u}, refs{&f_sx, &f_sy, &f_u};
    for (int f = 0; f < 3; ++f) {
      const auto e = relative_errors(*models[f], *refs[f]);
      add(scope + "." + kFields[f] + ".rel_l2", e.rel_l2, "||agent - FEM||_2 / ||FEM||_2");
      add(scope + "." + kFields[f] + ".rel_max", e.rel_max, "max |agent - FEM| / max |FEM|");
    }
    for (int f = 0; f < 2; ++f) {
      const auto r = ratios(*models[f], *refs[f], options.mask);
      add(scope + "." + kFields[f] + ".ratio_median_dev", std::abs(r.median - 1.0), "|median(agent / FEM) - 1|");
      add(scope + "." + kFields[f] + ".masked_fraction", double(r.masked_count) / double(std::max<std::size_t>(1, r.ratio.size())),
          "share of entries where |FEM| < mask * max |FEM|");
    }
  };
  add_scope("body", component(agent_sigma, 2, 0), component(fem_sigma, 2, 0), component(agent_sigma, 2, 1),
            component(fem_sigma, 2, 1), agent_fields.u, fem_u);

  // Sample lines.
  Eigen::Vector3d load_centre = Eigen::Vector3d::Zero();
  double total = 0;
  for (const auto& l : study.loads) {
    load_centre += l.force * grid.centre(l.cell);
    total += l.force;
  }
  load_centre /= total;
  const auto lines = standard_lines(grid, load_centre, options.depths);
  auto lines_csv = open_out(dir / "lines.csv");
  lines_csv << "model,line,arc_length [m],x [m],y [m]" << (dim == 3 ? ",z [m]" : "")
            << ",sigma_x [Pa],sigma_y [Pa],u_x [m],u_y [m]\n";
  for (std::size_t li = 0; li < lines.size(); ++li) {
    const auto& line = lines[li];
    std::vector<double> s[2][4];  // model, field (sx, sy, ux, uy)
    for (int i = 0; i < line.samples; ++i) {
      const Eigen::Vector3d p = line.point(i);
      const std::vector<double>* sig[2] = {&agent_sigma, &fem_sigma};
      const std::vector<double>* u[2] = {&agent.displacement, &fem_u};
      for (int m = 0; m < 2; ++m) {
        s[m][0].push_back(sample_cells(grid, *sig[m], 2, 0, p));
        s[m][1].push_back(sample_cells(grid, *sig[m], 2, 1, p));
        s[m][2].push_back(sample_nodes(grid, *u[m], dim, 0, p));
        s[m][3].push_back(sample_nodes(grid, *u[m], dim, 1, p));
        lines_csv << (m == 0 ? "agent" : "fem") << ',' << line.name << ',' << (p - line.from).norm();
        for (int a = 0; a < dim; ++a) lines_csv << ',' << p[a];
        for (int f = 0; f < 4; ++f) lines_csv << ',' << s[m][f].back();
        lines_csv << '\n';
      }
    }
    std::vector<double> ua, uf;
    for (int i = 0; i < line.samples; ++i) {
      ua.insert(ua.end(), {s[0][2][i], s[0][3][i]});
      uf.insert(uf.end(), {s[1][2][i], s[1][3][i]});
    }
    add_scope(line.name, s[0][0], s[1][0], s[0][1], s[1][1], ua, uf);
  }
  lines_csv.close();  // complete on disk before figures.py reads it
  if (!lines_csv) throw Error((dir / "lines.csv").string() + ": write failed");

  // Equilibrium: what each model returns at its supports against what was applied.
  const auto& d = agent.diagnostics;
  add("agent.equilibrium_dev", std::abs(d.rigid_reaction - d.applied) / d.applied,
      "|rigid reaction - applied| / applied (agent)");
  add("fem.equilibrium_dev", report::fem_equilibrium_dev(fem), "|reactions + applied| / |applied| (FEM)");
  add("agent.reach_fraction", double(d.agents_generated) / double(n_cells), "share of agents the load reaches");

  // One VTU with both models, their differences and ratios.
  {
    auto mesh = agent_study::output_mesh(study);
    const auto rx = ratios(component(agent_sigma, 2, 0), component(fem_sigma, 2, 0), options.mask);
    const auto ry = ratios(component(agent_sigma, 2, 1), component(fem_sigma, 2, 1), options.mask);
    std::vector<workbench::Field> cells;
    for (const char* n : {"agent_sigma_x [Pa]", "agent_sigma_y [Pa]", "fem_sigma_x [Pa]", "fem_sigma_y [Pa]",
                          "diff_sigma_x [Pa]", "diff_sigma_y [Pa]", "ratio_sigma_x [-]", "ratio_sigma_y [-]",
                          "ratio_masked_x [-]", "ratio_masked_y [-]", "generation [-]"})
      cells.push_back({n, 1, {}, {}, {}});
    for (std::size_t cell : study.mesh.cell_of_element) {
      const double v[] = {agent_sigma[2 * cell], agent_sigma[2 * cell + 1], fem_sigma[2 * cell], fem_sigma[2 * cell + 1],
                          agent_sigma[2 * cell] - fem_sigma[2 * cell], agent_sigma[2 * cell + 1] - fem_sigma[2 * cell + 1],
                          rx.ratio[cell], ry.ratio[cell], double(rx.masked[cell]), double(ry.masked[cell]),
                          double(agent.generation[cell])};
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
        const double ua = a < dim ? agent.displacement[n * dim + a] : 0.0, uf = a < dim ? fem_u[n * dim + a] : 0.0;
        points[0].values.push_back(ua);
        points[1].values.push_back(uf);
        points[2].values.push_back(ua - uf);
      }
    workbench::write_vtu(dir / "compare.vtu", mesh, points, cells);

    auto cells_csv = open_out(dir / "cells.csv");
    cells_csv << "cell,x [m],y [m]" << (dim == 3 ? ",z [m]" : "")
              << ",generation,agent_sigma_x [Pa],agent_sigma_y [Pa],fem_sigma_x [Pa],fem_sigma_y [Pa],ratio_sigma_x [-],"
                 "ratio_sigma_y [-],masked_x,masked_y\n";
    for (std::size_t e = 0; e < study.mesh.cell_of_element.size(); ++e) {
      const std::size_t cell = study.mesh.cell_of_element[e];
      const Eigen::Vector3d c = grid.centre(cell);
      cells_csv << e;
      for (int a = 0; a < dim; ++a) cells_csv << ',' << c[a];
      // (+ 0.0: a zero ratio of a negative reference is -0, which would print as "-0")
      cells_csv << ',' << agent.generation[cell] << ',' << agent_sigma[2 * cell] << ',' << agent_sigma[2 * cell + 1] << ','
                << fem_sigma[2 * cell] << ',' << fem_sigma[2 * cell + 1] << ',' << rx.ratio[cell] + 0.0 << ',' << ry.ratio[cell] + 0.0
                << ',' << int(rx.masked[cell]) << ',' << int(ry.masked[cell]) << '\n';
    }
    auto nodes_csv = open_out(dir / "nodes.csv");
    const auto nn = grid.node_counts();
    nodes_csv << "i,j" << (dim == 3 ? ",k" : "") << ",x [m],y [m]" << (dim == 3 ? ",z [m]" : "")
              << ",agent_u_x [m],agent_u_y [m]" << (dim == 3 ? ",agent_u_z [m]" : "") << ",fem_u_x [m],fem_u_y [m]"
              << (dim == 3 ? ",fem_u_z [m]" : "") << "\n";
    for (int k = 0; k < nn[2]; ++k)
      for (int j = 0; j < nn[1]; ++j)
        for (int i = 0; i < nn[0]; ++i) {
          const std::size_t n = grid.node_index(i, j, k);
          nodes_csv << i << ',' << j;
          if (dim == 3) nodes_csv << ',' << k;
          for (int a = 0; a < dim; ++a) nodes_csv << ',' << mesh.points[3 * n + a];
          for (int a = 0; a < dim; ++a) nodes_csv << ',' << agent.displacement[n * dim + a];
          for (int a = 0; a < dim; ++a) nodes_csv << ',' << fem_u[n * dim + a];
          nodes_csv << '\n';
        }
    // The agent's load steps, for the animation.
    auto steps_csv = open_out(dir / "steps.csv");
    steps_csv << "step,load [N],cell,generation,sigma_x [Pa],sigma_y [Pa]\n";
    for (int k = 1; k <= study.setup.steps; ++k) {
      const double factor = double(k) / study.setup.steps;
      const auto s = agent_study::evaluate(study, model, factor);
      for (std::size_t e = 0; e < study.mesh.cell_of_element.size(); ++e) {
        const std::size_t cell = study.mesh.cell_of_element[e];
        steps_csv << k << ',' << factor * total << ',' << e << ',' << s.generation[cell] << ','
                  << s.stress[cell * dim] << ',' << s.stress[cell * dim + 1] << '\n';
      }
    }
    if (!cells_csv || !nodes_csv || !steps_csv) throw Error(dir.string() + ": write failed");
  }
  add("time.agent_s", agent_seconds, "agent model, all load steps with output [s]");
  add("time.fem_s", fem_seconds, "FEM reference with output [s]");
  add("time.compare_s", seconds_since(t), "comparison and its output [s]");

  // Figures 8-11 and the animation, from the CSV files (compare/figures.py, matplotlib).
  double figures_seconds = 0;
  if (options.figures) {
    t = std::chrono::steady_clock::now();
    report::run_figure_script("compare/figures.py", dir,
                              study.setup.title.empty() ? file.path().stem().string() : study.setup.title, log);
    figures_seconds = seconds_since(t);
  }
  add("time.figures_s", figures_seconds, "figures and animation [s]");
  add("time.total_s", seconds_since(start), "the whole study [s]");

  // The gate, summary.json / summary.txt / junit.xml.
  nlohmann::json json;
  json["case"] = file.path().string();
  json["title"] = study.setup.title;
  json["model"] = "agent";
  json["agent"] = {{"rule_set", study.rules == agent::RuleSet::Patent ? "patent" : "conserving"},
                   {"alpha1", study.coefficients.alpha1}, {"alpha2", study.coefficients.alpha2},
                   {"alpha3", study.coefficients.alpha3}, {"beta", study.coefficients.beta},
                   {"gamma", study.coefficients.gamma}, {"poisson_decay", study.coefficients.decay()},
                   {"agents", n_cells}, {"agent_size", grid.size[0]},
                   {"applied", d.applied}, {"rigid_reaction", d.rigid_reaction}, {"passed_out", d.passed_out},
                   {"dropped", d.dropped}, {"agents_generated", d.agents_generated}};
  json["fem"] = {{"solver", fem.solver}, {"iterations", fem.iterations}, {"residual", fem.residual},
                 {"backward_error", fem.backward_error ? nlohmann::json(*fem.backward_error) : nlohmann::json()},
                 {"dofs", fem.n_dofs}, {"degree", fem.degree}, {"model", fem.model}};
  json["mask"] = options.mask;
  report::finish(dir, file.path().stem().string(), std::move(json), options.gate, {}, outcome, log);
  return outcome;
}

}  // namespace

CompareOutcome run_compare(const workbench::CaseFile& file, const fs::path& dir, std::ostream& log) {
  const auto options = read_compare_options(file.root());
  return options.model == "pbd" ? run_pbd_compare(file, options, dir, log) : run_agent_compare(file, options, dir, log);
}

}  // namespace compare

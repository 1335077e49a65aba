// The studies' bindings of the `workbench` Python module (docs/python.md), one per subcommand of
// the command line: each runs through the front doors (studies/studies.h) and returns a dict.
#include "arrays.h"
#include "bindings.h"

#include <compare/calibration_study.h>
#include <compare/summarize.h>
#include <studies/studies.h>

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace workbench_python {

namespace {

/// A list of dicts, one per item, each filled by `fill(dict, item)`.
template <class Items, class Fill>
py::list dict_list(const Items& items, Fill fill) {
  py::list out;
  for (const auto& item : items) {
    py::dict d;
    fill(d, item);
    out.append(d);
  }
  return out;
}

py::dict coefficients_dict(const agent::Coefficients& k) {
  py::dict out;
  for (const auto& [name, value] : agent_study::coefficient_values(k)) out[name.c_str()] = value;
  return out;
}

py::dict run_agent(const Case& c, const std::optional<fs::path>& output_dir, double load_factor,
                   const py::object& progress) {
  struct Out {
    agent_study::AgentState state;
    std::vector<double> centres, nodes;
    std::vector<std::size_t> cell_of_element;
    int dim;
    std::array<int, 3> cells;
    bool tiled = false;
    std::vector<std::int32_t> cell_coords, node_coords;  ///< box coordinates per slot id, per node id
    agent::Coefficients coefficients;
  };
  auto out = with_progress(progress, [&](std::ostream& log) {
    auto file = c.open();
    // With a folder, `workbench agent`'s run: its last step is the full load, solved once.
    std::optional<studies::AgentRun> run;
    if (output_dir) run.emplace(studies::run_agent_study(*file, *output_dir, log));
    const auto study = run ? std::move(run->study) : studies::open_agent_study(*file);
    const auto& grid = study.mesh.grid;
    auto state = [&] {
      if (run && load_factor == 1.0) return std::move(run->steps.back());
      auto model = agent_study::transfer_model(study);
      return agent_study::evaluate(study, model, load_factor);
    };
    Out o{state(), {}, {}, study.mesh.cell_of_element, grid.dim,
          {grid.cells[0], grid.cells[1], grid.dim == 3 ? grid.cells[2] : 1}, grid.tiled(), {}, {}, study.coefficients};
    for (std::size_t cell = 0; cell < grid.count(); ++cell) {
      const Eigen::Vector3d x = grid.centre(cell);
      o.centres.insert(o.centres.end(), {x[0], x[1], x[2]});
      const auto c = grid.coords(cell);
      o.cell_coords.insert(o.cell_coords.end(), {c[0], c[1], c[2]});
    }
    for (std::size_t node = 0; node < grid.node_count(); ++node) {
      const auto c = grid.node_coords(node);
      o.node_coords.insert(o.node_coords.end(), {c[0], c[1], c[2]});
    }
    o.nodes = agent_study::output_mesh(study).points;
    return o;
  });
  const std::size_t n = out.centres.size() / 3, dim = std::size_t(out.dim);
  py::dict r;
  r["dim"] = out.dim;
  r["cells"] = py::make_tuple(out.cells[0], out.cells[1], out.cells[2]);
  r["tiled"] = out.tiled;
  r["cell_centres"] = take(std::move(out.centres), {ssize(n), 3});
  r["cell_coords"] = take(std::move(out.cell_coords), {ssize(n), 3});
  const std::size_t node_ids = out.node_coords.size() / 3;
  r["node_coords"] = take(std::move(out.node_coords), {ssize(node_ids), 3});
  r["node_points"] = take(std::move(out.nodes), {ssize(out.state.displacement.size() / dim), 3});
  workbench_python::add_state_fields(r, out.state, out.dim);  // every field of agent::kStateFields, diagnostics
  r["cell_of_element"] = take(std::move(out.cell_of_element), {ssize(n)});
  r["coefficients"] = coefficients_dict(out.coefficients);
  return r;
}

py::dict fem_dict(fem_reference::FemResult&& f) {
  py::dict r;
  const auto n_cells = ssize(f.cell_count()), n_nodes = ssize(f.node_count());
  r["dim"] = f.dim;
  r["degree"] = f.degree;
  r["model"] = f.model;
  r["cells"] = f.cells;
  r["ranks"] = f.ranks;
  r["n_dofs"] = f.n_dofs;
  r["n_active_cells"] = f.n_active_cells;
  r["node_points"] = take(std::move(f.node_points), {n_nodes, 3});
  r["node_displacement"] = take(std::move(f.node_displacement), {n_nodes, py::ssize_t(f.dim)});
  r["cell_centres"] = take(std::move(f.cell_centres), {n_cells, 3});
  for (auto [name, v] : {std::pair{"sigma_x", &f.sigma_x}, {"sigma_y", &f.sigma_y}, {"sigma_z", &f.sigma_z},
                         {"tau_xy", &f.tau_xy}, {"tau_yz", &f.tau_yz}, {"tau_xz", &f.tau_xz},
                         {"von_mises", &f.von_mises}})
    r[name] = take(std::move(*v), {n_cells});
  r["reactions"] = dict_list(f.reactions, [](py::dict& d, const fem_reference::GroupReaction& g) {
    d["group"] = g.group;
    d["kind"] = g.kind;
    d["force_N"] = g.force;
  });
  r["applied_N"] = f.applied;
  r["solver"] = f.solver;
  r["iterations"] = f.iterations;
  r["residual"] = f.residual;
  r["backward_error"] = f.backward_error ? py::cast(*f.backward_error) : py::none();
  r["l2_error"] = f.l2_error;
  r["h1_error"] = f.h1_error;
  py::dict seconds;
  seconds["mesh"] = f.mesh_seconds;
  seconds["setup"] = f.setup_seconds;
  seconds["assemble"] = f.assemble_seconds;
  seconds["solve"] = f.solve_seconds;
  seconds["output"] = f.output_seconds;
  r["seconds"] = seconds;
  return r;
}

py::dict run_fem(const Case& c, const std::optional<fs::path>& output_dir, const py::object& progress) {
  auto result = with_progress(progress, [&](std::ostream& log) {
    auto file = c.open();
    if (!output_dir) return fem_reference::solve_fem(studies::open_fem_study(*file), {}, &log);
    return studies::run_fem_study(*file, *output_dir, log).result;
  });
  return fem_dict(std::move(result));
}

py::dict run_compare(const Case& c, const fs::path& output_dir, const py::object& progress) {
  auto outcome = with_progress(progress, [&](std::ostream& log) {
    auto file = c.open();
    return studies::run_compare_study(*file, output_dir, log).outcome;
  });
  py::dict metrics, meanings, reference_errors, agents_only;
  py::list not_modelled;
  for (const auto& m : outcome.metrics) {
    metrics[py::str(m.name)] = m.value;
    meanings[py::str(m.name)] = m.meaning;
    if (!std::isnan(m.reference_error)) reference_errors[py::str(m.name)] = m.reference_error;
    if (!std::isnan(m.agents_only)) agents_only[py::str(m.name)] = m.agents_only;
    if (!m.modelled) not_modelled.append(m.name);
  }
  py::list failures;
  for (const auto& f : outcome.failures) failures.append(py::make_tuple(f.metric, f.value, f.limit));
  py::dict r;
  r["metrics"] = metrics;
  r["meanings"] = meanings;
  r["reference_errors"] = reference_errors;  // the reference's own error, beside each error metric
  r["agents_only"] = agents_only;            // the agents alone, beside each metric of closed-form layers
  r["not_modelled"] = not_modelled;          // metrics of components the rule set does not model
  py::list warning_list;
  for (const auto& w : outcome.warnings) warning_list.append(w);
  r["warnings"] = warning_list;
  r["gate_failures"] = failures;
  r["gated"] = outcome.gated;
  r["fields"] = workbench_python::compared_fields_dict(std::move(outcome.fields));
  return r;
}

/// front.json as a dict (the file the study wrote: one description of a front, read the same way
/// from Python and from disk).
py::object run_front(const Case& c, const fs::path& output_dir, const py::object& progress) {
  const auto folder = with_progress(progress, [&](std::ostream& log) {
    auto file = c.open();
    return studies::run_front_study(*file, output_dir, log).folder;
  });
  std::ifstream in(folder / "front.json");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return py::module_::import("json").attr("loads")(text);
}

py::dict run_calibrate(const Case& c, const fs::path& output_dir, const py::object& progress) {
  auto result = with_progress(progress, [&](std::ostream& log) {
    auto file = c.open();
    return studies::run_calibrate_study(*file, output_dir, log).result;
  });
  py::dict r;
  r["start"] = coefficients_dict(result.start);
  r["best"] = coefficients_dict(result.best);
  r["objective_start"] = result.objective_start;
  r["objective_best"] = result.objective_best;
  r["start_objectives"] = result.start_objectives;
  r["evaluations"] = result.evaluations;
  r["sensitivity"] = dict_list(result.sensitivity, [](py::dict& d, const compare::Sensitivity& s) {
    d["name"] = s.name;
    d["objective_minus"] = s.objective_minus;
    d["objective_plus"] = s.objective_plus;
    d["curvature"] = s.curvature;
    d["pinned"] = s.pinned;
  });
  py::dict held_out;  // report.json's held_out: per case, each field's error before and after (None: not solved)
  for (const auto& h : result.held_out) {
    auto errors = [&](const compare::Score& s) {
      py::dict e;
      for (std::size_t k = 0; k < compare::kFieldCount; ++k)
        if (compare::kFields[k].in(h.dim)) e[compare::kFields[k].name] = s.load_refused ? py::none() : py::cast(s.error[k]);
      return e;
    };
    held_out[py::str(h.name)] = py::dict(py::arg("before") = errors(h.before), py::arg("after") = errors(h.after));
  }
  r["held_out"] = held_out;
  return r;
}

py::dict run_pbd(const Case& c, const py::object& progress) {
  struct Out {
    std::vector<double> rest, frames, times;
    std::vector<int> pinned;
    std::size_t written = 0, nodes = 0;
  };
  auto out = with_progress(progress, [&](std::ostream& log) {
    auto file = c.open();
    auto study = studies::open_pbd_study(*file);
    const auto& setup = study.setup;
    Out o;
    o.nodes = study.mesh.mesh.points.size();
    for (const auto& p : study.mesh.mesh.points) o.rest.insert(o.rest.end(), {p[0], p[1], p[2]});
    o.pinned = study.pinned;
    pbd::Solver solver(study.model);
    pbd_study::step_frames(study, solver, [&](int frame) {  // the frames `workbench pbd` writes
      for (const auto& x : study.model.particles.x) o.frames.insert(o.frames.end(), {x[0], x[1], x[2]});
      o.times.push_back(frame * setup.step.dt);
      ++o.written;
    }, log);
    return o;
  });
  py::dict r;
  r["rest_positions"] = take(std::move(out.rest), {ssize(out.nodes), 3});
  r["positions"] = take(std::move(out.frames), {ssize(out.written), ssize(out.nodes), 3});
  r["times"] = take(std::move(out.times), {ssize(out.written)});
  r["pinned"] = take(std::move(out.pinned), {ssize(out.pinned.size())});
  return r;
}

}  // namespace

/// The studies, one per subcommand of the command line.
void bind_studies(py::module_& m) {
  // Each call's docstring: its arguments, then every key of what it returns (docs/python.md has the table).
  m.def("run_agent", &run_agent, py::arg("case"), py::arg("output_dir") = py::none(), py::arg("load_factor") = 1.0,
        py::arg("progress") = py::none(),
        "The agent model, as `workbench agent`.\n\n"
        "Arguments: case (workbench.Case); output_dir (also write `workbench agent`'s files there, whole or not at "
        "all); load_factor (the load times this); progress (a callable given each progress line).\n\n"
        "Returns a dict: one array per row of agent_fields() (face_force [N], stress, shear, von_mises [Pa], strain, "
        "generation, displacement [m]), cell_centres, node_points [m], cell_coords, node_coords (box i, j, k), "
        "cell_of_element (the agent of mesh element e), dim, cells, tiled, diagnostics (dict, forces in N), "
        "coefficients (every coefficient in effect, by name).");
  m.def("run_fem", &run_fem, py::arg("case"), py::arg("output_dir") = py::none(), py::arg("progress") = py::none(),
        "The FEM reference, as `workbench fem`.\n\n"
        "Arguments: case (workbench.Case); output_dir (also write `workbench fem`'s files there); progress (a "
        "callable given each progress line).\n\n"
        "Returns a dict: sigma_x, sigma_y, sigma_z, tau_xy, tau_yz, tau_xz, von_mises [Pa] per cell (gmsh element "
        "order), node_displacement [m] (nodes x dim), node_points, cell_centres [m], reactions (per group: group, "
        "kind, force_N), applied_N, solver, iterations, residual, backward_error, l2_error, h1_error, seconds "
        "(mesh, setup, assemble, solve, output), dim, degree, model, cells, ranks, n_dofs, n_active_cells.");
  m.def("compare", &run_compare, py::arg("case"), py::arg("output_dir"), py::arg("progress") = py::none(),
        "`workbench compare`: writes everything into output_dir (report.html included).\n\n"
        "Arguments: case (workbench.Case); output_dir (the output folder); progress (a callable given each "
        "progress line).\n\n"
        "Returns a dict: metrics (name: value, summary.json's names), meanings (name: text), reference_errors (name: "
        "the reference's own error), agents_only (name: the same error of the agents alone, where the rule set adds "
        "closed-form layers), not_modelled (list: the metrics of stress components the rule set does not model), "
        "warnings (list), gate_failures (list of (metric, value, limit)), gated (how "
        "many limits were checked), and fields: the compared fields as arrays in the CSV files' row order, "
        "fields['cells'] (cells.csv: point, agent_sigma, fem_sigma, diff_sigma, ratio_sigma, masked, far, "
        "generation, agent_<field>, fem_<field>), fields['nodes'] (nodes.csv: box_coords, point, agent_u, fem_u, "
        "diff_u, far), fields['lines'][name] (lines.csv: segment (0, then one more after each stretch of air the "
        "line crosses: break a plot where it changes), arc_length, point, agent_sigma, fem_sigma, agent_u, fem_u, "
        "agent_<field>, fem_<field>); a PBD comparison has fields['lines']['centreline'] only.");
  m.def("front", &run_front, py::arg("case"), py::arg("output_dir"), py::arg("progress") = py::none(),
        "`workbench front`: the cost-accuracy front; writes everything into output_dir.\n\n"
        "Arguments: case (workbench.Case, with [front]: an agent case, or a PBD case against its FEM strip); "
        "output_dir; progress (a callable given each progress line).\n\n"
        "Returns front.json as a dict: points (model \"agent\", \"pbd\" or \"fem\", label, size, work, seconds "
        "{min, median}, errors), metrics, headline, verdicts "
        "(point, metric, dominated_by, speedup, speedup_at_most, speedup_at_least, below_floor), crossovers, "
        "reference {errors}, case_point, skipped, gate {checked, failed, failures}, machine.");
  m.def("calibrate", &run_calibrate, py::arg("calibration"), py::arg("output_dir"), py::arg("progress") = py::none(),
        "`workbench calibrate` on a calibration file; writes report.txt, report.json, report.html and "
        "calibrated/<case>.toml into output_dir.\n\n"
        "Arguments: calibration (workbench.Case of a calibration file, docs/calibration.md); output_dir; progress "
        "(a callable given each progress line).\n\n"
        "Returns a dict: start, best (every coefficient by name), objective_start, objective_best, "
        "start_objectives (the best objective from each start), evaluations, sensitivity (per free coefficient: "
        "name, objective_minus, objective_plus, curvature, pinned), held_out (per [[calibrate.held_out]] case: "
        "before, after: each field's error at the start and at the fit; None where the model cannot be solved).");
  m.def(
      "summarize",
      [](const std::vector<fs::path>& folders) {
        const auto table = compare::summarize(folders);
        py::list rows;
        for (const auto& r : table.rows)
          rows.append(py::dict(py::arg("folder") = r.folder, py::arg("parameters") = r.parameters,
                               py::arg("metrics") = r.metrics, py::arg("not_modelled") = r.not_modelled));
        return py::dict(py::arg("parameters") = table.parameters, py::arg("metrics") = table.metrics,
                        py::arg("rows") = rows);
      },
      py::arg("folders"),
      "`workbench summarize`: the summaries of compare and calibrate output folders as one table.\n\n"
      "Arguments: folders (a list of output folders).\n\nReturns a dict: `parameters` "
      "(the case keys that differ between the folders), `metrics` (every name), `rows` (per folder: `folder`, "
      "`parameters`, `metrics`, `not_modelled`: the metrics of components its rule set does not model).");
  m.def("run_pbd", &run_pbd, py::arg("case"), py::arg("progress") = py::none(),
        "The PBD model, stepped as `workbench pbd` does; writes nothing.\n\n"
        "Arguments: case (workbench.Case); progress (a callable given each progress line).\n\n"
        "Returns a dict: positions [m] (written frames x nodes x 3), times [s] (per written frame), "
        "rest_positions [m] (nodes x 3), pinned (node ids).");
}

}  // namespace workbench_python

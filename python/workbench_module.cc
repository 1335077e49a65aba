// The `workbench` Python module (pybind11, docs/python.md): case files in, numpy arrays and dicts out.
// A thin layer over the modules' front doors (studies/studies.h), the ones the command line calls;
// no model code and no study flow lives here. This file: the case, the tables, the calibration
// objective and the module itself; the studies' calls are in python/bind_studies.cc.
#include "arrays.h"
#include "bindings.h"

#include <compare/calibration_study.h>
#include <fem_reference/mpi.h>
#include <workbench/error.h>

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace py = pybind11;
namespace fs = std::filesystem;

using workbench_python::Case;
using workbench_python::with_progress;

namespace {

/// A Python value as a TOML node: bool, int, float, str, list/tuple, dict (numpy scalars and arrays too).
void insert(toml::table& table, const std::string& key, const py::handle& value);
toml::array to_array(const py::handle& list) {
  toml::array out;
  for (const auto& item : list) {
    toml::table wrapper;
    insert(wrapper, "v", item);
    out.push_back(std::move(*wrapper.get("v")));
  }
  return out;
}
toml::table to_table(const py::dict& dict) {
  toml::table out;
  for (const auto& [key, value] : dict) insert(out, py::str(key), value);
  return out;
}
void insert(toml::table& table, const std::string& key, const py::handle& item) {
  // numpy scalars and arrays as the Python values they hold (np.int64 is no int, an array no list).
  py::object value = py::reinterpret_borrow<py::object>(item);
  if (py::isinstance<py::array>(value))
    value = value.attr("tolist")();
  else if (py::isinstance(value, py::module_::import("numpy").attr("generic")))
    value = value.attr("item")();
  if (py::isinstance<py::bool_>(value))
    table.insert_or_assign(key, value.cast<bool>());
  else if (py::isinstance<py::int_>(value))
    table.insert_or_assign(key, value.cast<long long>());
  else if (py::isinstance<py::float_>(value))
    table.insert_or_assign(key, value.cast<double>());
  else if (py::isinstance<py::str>(value))
    table.insert_or_assign(key, value.cast<std::string>());
  else if (py::isinstance<py::dict>(value))
    table.insert_or_assign(key, to_table(value.cast<py::dict>()));
  else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value))
    table.insert_or_assign(key, to_array(value));
  else
    throw workbench::Error(key + ": a case value must be a bool, number, string, list or dict, not " +
                           std::string(py::str(value.get_type().attr("__name__"))));
}

/// The calibration objective on a set of study cases, each FEM reference solved once: for fitting
/// with any optimiser (scipy.optimize in notebooks/calibration_scipy.ipynb).
class Objective {
 public:
  /// `weights`: field name (a row of compare::kFields) -> weight; the rest at the calibration's defaults.
  Objective(const std::vector<Case>& cases, const std::string& rule_set, const std::map<std::string, double>& weights,
            const py::object& progress) {
    const auto named = agent::rule_set_named(rule_set);
    if (!named) {
      std::string names;
      for (agent::RuleSet r : agent::kRuleSets) names += std::string(names.empty() ? "" : ", ") + "\"" + agent::rule_set_name(r) + "\"";
      throw workbench::Error("rule_set: must be one of " + names + ", not \"" + rule_set + "\"");
    }
    rules_ = *named;
    for (const auto& [name, value] : weights) {
      const auto* f = std::find_if(std::begin(compare::kFields), std::end(compare::kFields),
                                   [&](const auto& x) { return name == x.name; });
      if (f == std::end(compare::kFields)) throw workbench::Error("weights: unknown field \"" + name + "\" (compare::kFields)");
      if (!(value >= 0 && std::isfinite(value))) throw workbench::Error("weights: " + name + " must be >= 0");
      weights_.field[std::size_t(f - compare::kFields)] = value;
    }
    cases_ = with_progress(progress, [&](std::ostream& log) {
      std::vector<compare::CalibrationCase> out;
      for (const auto& c : cases) {
        auto file = c.open();
        auto cc = compare::load_calibration_case(*file, nullptr, nullptr, log);  // as `workbench calibrate` does
        out.push_back(std::move(cc));
      }
      return out;
    });
  }
  /// J at the coefficients: [alpha1, alpha2, alpha3, beta, gamma], or a dict of any of
  /// agent::kCoefficients (the rest at the library's defaults; poisson_decay follows alpha2 as
  /// in `workbench calibrate`). Each case keeps its own [agent] readings; the cases are scored on
  /// every core.
  double operator()(const agent::Coefficients& k) const {
    py::gil_scoped_release release;
    return compare::objective(cases_, k, rules_, weights_, nullptr, every_core());
  }
  py::list scores(const agent::Coefficients& k) const {
    std::vector<compare::Score> per_case;
    {
      py::gil_scoped_release release;
      compare::objective(cases_, k, rules_, weights_, &per_case, every_core());
    }
    py::list out;
    for (std::size_t i = 0; i < per_case.size(); ++i) {
      py::dict d;
      d["case"] = cases_[i].name;
      for (std::size_t k = 0; k < compare::kFieldCount; ++k)  // every field compared in the case's dimension
        if (compare::kFields[k].in(cases_[i].study.mesh.grid.dim)) d[compare::kFields[k].name] = per_case[i].error[k];
      out.append(d);
    }
    return out;
  }

 private:
  /// The seed's rule sets' coefficients (alpha1, alpha2, alpha3, beta, gamma: the order of the call's values).
  static agent::Coefficients seed_coefficients(const std::array<double, 5>& values) {
    agent::Coefficients k;
    static constexpr const char* kSeedNames[] = {"alpha1", "alpha2", "alpha3", "beta", "gamma"};
    for (std::size_t i = 0; i < values.size(); ++i) agent::find_coefficient(kSeedNames[i])->set(k, values[i]);
    return k;
  }
  /// Named coefficients (any row of agent::kCoefficients), the rest at the library's defaults.
  static agent::Coefficients named_coefficients(const std::map<std::string, double>& values) {
    agent::Coefficients k;
    for (const auto& [name, value] : values) {
      const auto* c = agent::find_coefficient(name);
      if (!c) throw workbench::Error("coefficients: unknown coefficient \"" + name + "\"");
      if (const auto why = c->problem(value); !why.empty()) throw workbench::Error("coefficients: " + name + " " + why);
      c->set(k, value);
    }
    return k;
  }
  /// One process, its cases on every core (the total is the same, bit for bit, for any count).
  static compare::CaseShare every_core() {
    return {0, 1, std::max(1, int(std::thread::hardware_concurrency()))};
  }
  friend void bind_objective(py::module_& m);

  std::vector<compare::CalibrationCase> cases_;
  agent::RuleSet rules_ = agent::RuleSet::Conserving;
  compare::ObjectiveWeights weights_;
};

void bind_objective(py::module_& m) {
  py::class_<Objective>(m, "Objective", "The calibration objective over study cases (FEM solved once per case)")
      .def(py::init([](const std::vector<Case>& cases, const std::string& rule_set, const py::object& progress,
                       const py::kwargs& fields) {
             // Each keyword names a field of compare::kFields: sigma_x=1.0, tau_xy=0.5, ...
             std::map<std::string, double> weights;
             for (const auto& [name, value] : fields) weights[py::cast<std::string>(name)] = py::cast<double>(value);
             return new Objective(cases, rule_set, weights, progress);
           }),
           py::arg("cases"), py::arg("rule_set") = "conserving", py::arg("progress") = py::none(),
           "Arguments: cases (a list of workbench.Case, each a study case; its FEM reference is solved once, now); "
           "rule_set (\"patent\", \"conserving\" or \"directional\"); progress (a callable given each progress line); "
           "the weights per field as keywords (compare::kFields: sigma_x, sigma_y, displacement, tau_xy, von_mises, "
           "u_x, ...; default sigma_y = displacement = 1, the rest 0).")
      .def(
          "__call__", [](const Objective& o, const std::array<double, 5>& v) { return o(Objective::seed_coefficients(v)); },
          py::arg("coefficients"), "Returns J (float) at [alpha1, alpha2, alpha3, beta, gamma]")
      .def(
          "__call__",
          [](const Objective& o, const std::map<std::string, double>& v) { return o(Objective::named_coefficients(v)); },
          py::arg("coefficients"),
          "Returns J (float) at named coefficients, e.g. {\"fan_angle\": 60, \"diffusion_length\": 0.002}; the rest "
          "at the library's defaults")
      .def(
          "scores", [](const Objective& o, const std::array<double, 5>& v) { return o.scores(Objective::seed_coefficients(v)); },
          py::arg("coefficients"),
          "Returns a list, per case: a dict of `case` (its name) and each field's relative error (the fields "
          "compared in its dimension), at [alpha1, alpha2, alpha3, beta, gamma]")
      .def(
          "scores",
          [](const Objective& o, const std::map<std::string, double>& v) { return o.scores(Objective::named_coefficients(v)); },
          py::arg("coefficients"), "Returns each case's relative errors (as above) at named coefficients");
}

/// workbench.coefficients(): every row of agent::kCoefficients as a dict.
py::list coefficient_table() {
  py::list out;
  for (const auto& c : agent::kCoefficients) {
    py::dict d;
    d["name"] = c.name;
    d["unit"] = c.unit;
    d["meaning"] = c.meaning;
    py::list rules;
    for (agent::RuleSet r : agent::kRuleSets)
      if (c.used_by(r)) rules.append(agent::rule_set_name(r));
    d["rule_sets"] = rules;
    d["default"] = c.default_value();
    d["min"] = c.min;
    d["max"] = c.max;
    d["min_open"] = c.min_open;
    d["max_open"] = c.max_open;
    d["integer"] = c.integer;
    d["fitted"] = c.fitted;
    d["fit_min"] = c.fit_min;
    d["fit_max"] = c.fit_max;
    py::list choices;  // a named choice's names (its value is the index); empty for a number
    for (int i = 0; i < c.choice_count; ++i) choices.append(c.choices[i]);
    d["choices"] = choices;
    out.append(d);
  }
  return out;
}

/// workbench.Case: a case file or a dict of tables.
void bind_case(py::module_& m) {
  py::class_<Case>(m, "Case", "A study's case: a case file, or a dict with the same tables (docs/case-file.md)")
      .def(py::init([](const fs::path& path) {
             Case c{path, {}};
             c.open();  // a missing file or a syntax error is raised now
             return c;
           }),
           py::arg("path"), "Reads a case file (TOML).")
      .def_static(
          "from_dict",
          [](const py::dict& tables, const fs::path& name) {
            std::ostringstream text;
            text << to_table(tables);
            Case c{name, text.str()};
            c.open();
            return c;
          },
          py::arg("tables"), py::arg("name") = fs::path("case.toml"),
          "A case from a dict of tables; `name` stands for the file in messages and its folder resolves "
          "relative paths (the mesh file).")
      .def_property_readonly("path", [](const Case& c) { return c.path; })
      .def_property_readonly("toml", [](const Case& c) {
        if (!c.text.empty()) return c.text;
        std::ifstream in(c.path);
        return std::string(std::istreambuf_iterator<char>(in), {});
      }, "The case as TOML text");
}

/// The tables the module reads its names from: coefficients, agent fields.
void bind_tables(py::module_& m) {
  m.def("coefficients", &coefficient_table,
        "The table of the agent model's coefficients (agent/coefficients.h): name, unit, meaning, the rule sets "
        "that use it, default, admissible range, whether a calibration fits it and its default bounds.");
  m.def("agent_fields", &workbench_python::state_fields_list,
        "The table of the agent model's fields (agent/state.h): name, unit, place, the columns per dimension, the "
        "VTU layout and the compared fields (compare::kFields) each gives.");
}

}  // namespace

PYBIND11_MODULE(workbench, m) {
  m.doc() = "The deformation-model workbench from Python: agent model, FEM reference, comparison, calibration, "
            "PBD model (docs/python.md)";
  // Every call returns numpy arrays: without numpy, say so now, before any study runs and writes.
  try {
    py::module_::import("numpy");
  } catch (py::error_already_set& e) {
    throw py::import_error(std::string("workbench needs numpy, which this Python cannot import (") + e.what() +
                           "): install Debian's python3-numpy, or use /usr/bin/python3 (docs/python.md)");
  }
  py::register_exception<workbench::Error>(m, "Error", PyExc_RuntimeError);
  fem_reference::configure_singleton_mpi();  // as the command line does: the same start-up, a session folder of its own

  bind_case(m);
  bind_tables(m);
  workbench_python::bind_studies(m);
  bind_objective(m);
}

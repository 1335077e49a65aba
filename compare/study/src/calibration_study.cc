// The calibration as a workbench study: the calibration file, each case's reference, the report and the calibrated case files.
#include <compare/calibration_study.h>
#include <schema/every_section.h>
#include <compare/compare_study.h>
#include <compare/same_body.h>

#include "report.h"

#include <fem_reference/fem_case.h>
#include <fem_reference/mpi.h>
#include <workbench/case_edit.h>
#include <workbench/error.h>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <memory>
#include <ostream>
#include <sstream>
#include <thread>

namespace compare {

namespace fs = std::filesystem;
using workbench::Error;
using workbench::Range;

namespace {

/// [[calibrate.case]] (file, weight) and [[calibrate.held_out]] (file). A case's name (its file's
/// stem) names its calibrated/<name>.toml and its rows: one case per name.
void read_case_lists(const workbench::CaseTable& t, CalibrationPlan& plan) {
  const auto cases = t.tables("case");
  if (cases.empty()) t.fail("case", "missing (at least one [[calibrate.case]] with the file of a study case)");
  std::vector<std::string> names;
  auto add_case = [&](const workbench::CaseTable& c, std::vector<fs::path>& files) {
    files.push_back(c.path("file", std::nullopt));
    const std::string name = files.back().stem().string();
    if (std::find(names.begin(), names.end(), name) != names.end())
      c.fail("file", "a case named \"" + name + "\" is listed already: each case's file name must differ (calibrated/" + name + ".toml)");
    names.push_back(name);
  };
  for (const auto& c : cases) {
    add_case(c, plan.case_files);
    plan.case_weights.push_back(c.number("weight", 1.0, Range::positive()));
  }
  for (const auto& c : t.tables("held_out")) add_case(c, plan.held_out_files);
}

}  // namespace

CalibrationPlan read_calibration_plan(const workbench::CaseFile& file) {
  const auto root = file.root();
  root.text("title", "");
  const auto t = root.table("calibrate");
  CalibrationPlan plan;
  auto& o = plan.options;
  o.rules = agent_study::read_rule_set(t, agent::RuleSet::Conserving);
  if (t.has("readings")) plan.readings = agent_study::read_readings(t, o.rules);
  o.starts = t.integer("starts", 8, 1, 1000);
  o.seed = std::uint64_t(t.integer("seed", 1, 0, 2147483647));
  o.max_evaluations = t.integer("max_evaluations", 400, 1, 1000000);
  o.tolerance = t.number("tolerance", 1e-6, Range{0.0, 1.0, true, true});
  o.threads = t.integer("threads", 0, 0, 1024);
  plan.cross_validate = t.flag("cross_validate", true);
  const auto w = t.table("objective");
  // One weight per field of the one field table (compare::kFields).
  double weight_sum = 0;
  for (std::size_t k = 0; k < kFieldCount; ++k)
    weight_sum += o.weights.field[k] = w.number(kFields[k].name, o.weights.field[k], Range::non_negative());
  if (weight_sum <= 0) w.fail("sigma_y", "at least one field (compare::kFields: sigma_x, sigma_y, displacement, ...) must have a positive weight");
  const std::string scope = w.text("scope", "body", {"body", "far", "lines"});
  o.weights.lines = scope == "lines";
  o.weights.far = scope == "far";
  w.refuse_renamed("far_distance_mm", "far_distance", "in metres: far_distance_mm / 1000");
  o.weights.far_distance = w.number("far_distance", 0.0, Range::non_negative());
  o.weights.depths = w.numbers("depths", o.weights.depths, Range::open(0.0, 1.0));
  o.weights.keep_load = t.flag("keep_load", true);

  read_case_lists(t, plan);
  // Per coefficient (agent::kCoefficients): the library's value as the start, the table's fit
  // bounds, its range for what a file gives. Free by default: what the rule set uses, but gamma.
  int n_free = 0;
  for (std::size_t i = 0; i < kCoefficientCount; ++i) {
    const auto& c = agent::kCoefficients[i];
    const Range valid{c.min, c.max, c.min_open, c.max_open};
    const auto p = t.table(c.name);
    auto& param = o.parameters[i];
    param.name = c.name;
    param.free = p.flag("free", std::string(c.name) != "gamma" && c.used_by(o.rules));
    param.lo = p.number("min", c.fit_min, valid);
    param.hi = p.number("max", c.fit_max, valid);
    plan.start_given[i] = p.has("start");
    param.start = p.number("start", c.default_value(), valid);
    if (param.free && !(param.lo < param.hi))
      p.fail("max", "must be greater than min (" + std::to_string(param.lo) + ")");
    if (param.free && plan.start_given[i] && (param.start < param.lo || param.start > param.hi))
      p.fail("start", "must lie within [min, max]");
    n_free += param.free;
  }
  const auto& alpha2 = o.parameters[agent::coefficient_index("alpha2")], &alpha3 = o.parameters[agent::coefficient_index("alpha3")];
  if (o.rules == agent::RuleSet::Conserving && alpha2.free && alpha3.free && alpha2.lo <= 0 && alpha3.lo <= 0)
    t.table("alpha2").fail("min", "alpha2 and alpha3 may not both reach 0 in the conserving rule set (give one a min > 0)");
  if (n_free == 0) t.fail("alpha2", "no coefficient is free: nothing to fit");
  return plan;
}

std::string with_coefficients(const std::string& text, const fs::path& case_dir, const agent::Coefficients& k,
                              agent::RuleSet rules, const std::optional<agent::Readings>& readings) {
  std::vector<std::pair<std::string, std::string>> agent{{"rule_set", workbench::toml_string(agent::rule_set_name(rules))}};
  std::vector<std::string> not_acting;  // the threshold not in effect: a case names one of the two
  for (const auto& c : agent::kCoefficients)
    if (!c.acts_in(k)) not_acting.push_back(c.name);
    else if (!c.integer)  // poisson_decay too; `directions` is the case's own
      agent.emplace_back(c.name, workbench::toml_number(c.get(k)));
  if (readings) agent.emplace_back("readings", workbench::toml_strings(agent_study::names_of(*readings)));
  std::string out = text;
  if (auto file = toml::parse(text)["mesh"]["file"].value<std::string>(); file && fs::path(*file).is_relative())
    out = workbench::set_case_keys(out, "mesh", {{"file", workbench::toml_string(fs::absolute(case_dir / *file).lexically_normal().string())}});
  try {
    return workbench::set_case_keys(workbench::remove_case_keys(out, "agent", not_acting), "agent", agent);
  } catch (const Error& e) {
    throw Error(std::string("calibrate: ") + e.what());
  }
}

namespace {

/// The case file again, with the fitted [agent] coefficients and an absolute mesh path.
void write_calibrated_case(const fs::path& original, const fs::path& target, const agent::Coefficients& k,
                           agent::RuleSet rules, const std::optional<agent::Readings>& readings, const std::string& note) {
  std::ifstream in(original);
  std::stringstream text;
  text << in.rdbuf();
  const std::string out = with_coefficients(text.str(), original.parent_path(), k, rules, readings);
  report::write_text(target, "# " + note + "\n" + out);
}

std::string coefficient_row(const agent::Coefficients& k) {
  std::ostringstream s;
  s << std::setprecision(4);
  for (std::size_t i = 0; i < kCoefficientCount; ++i)
    s << (i ? ", " : "") << agent::kCoefficients[i].name << " " << agent::kCoefficients[i].get(k);
  return s.str();
}

}  // namespace

CalibrationCase load_calibration_case(const workbench::CaseFile& case_file, const agent::Readings* readings,
                                      const workbench::CaseTable* readings_key, std::ostream& log) {
  CalibrationCase c;
  c.name = case_file.path().stem().string();
  // Checked as every front door checks a case (studies/studies.h): every section, unknown keys
  // refused, before the mesh is read.
  schema::check_every_section(case_file);
  const auto compare_options = read_compare_options(case_file.root());
  if (compare_options.model != "agent")
    case_file.root().table("compare").fail("model", "calibration fits the agent model: a case with model = \"agent\"");
  c.study = agent_study::load_agent_study(case_file);
  if (readings) {
    c.study.readings = *readings;
    agent_study::check_readings_fit_loads(c.study, *readings_key);
  }
  const auto problem = fem_reference::problem_from_case(case_file);
  // The case's own reference ([compare.reference]; the 3D default converged), solved as `workbench
  // compare` solves it, without its files.
  const auto options = reference_options(compare_options, c.study);
  for (const auto& w : check_reference_body(case_file, c.study, options)) log << c.name << ": warning: " << w << "\n";
  log << c.name << ": solving the reference once\n" << std::flush;
  auto reference = solve_reference(problem, options, c.study.mesh, {}, log);
  c.reference = std::move(reference.fields);
  c.reference_level = level_json(reference);
  c.reference_limits = reference.limits_judgement();
  return c;
}

namespace {

using CaseFiles = std::vector<std::unique_ptr<workbench::CaseFile>>;

/// Every case file of `files` read and its sections checked: a bad one is refused before any
/// reference is solved.
CaseFiles open_cases(const std::vector<fs::path>& files) {
  CaseFiles out;
  for (const auto& f : files) {
    out.push_back(std::make_unique<workbench::CaseFile>(f));
    schema::check_every_section(*out.back());
  }
  return out;
}

/// The load cases of `files`, fitted or held out (`what`): the agent study, and the FEM reference
/// solved once; under MPI on every rank, the references across the ranks, bad input one line.
std::vector<CalibrationCase> load_cases(const workbench::CaseFile& file, const CalibrationPlan& plan,
                                        const CaseFiles& files, const char* what, std::ostream& log) {
  std::vector<CalibrationCase> cases;
  const auto calibrate_table = file.root().table("calibrate");
  for (std::size_t i = 0; i < files.size(); ++i) {
    const workbench::CaseFile& case_file = *files[i];
    log << "calibrate: " << what << " " << i + 1 << "/" << files.size() << " ";
    CalibrationCase c;
    try {
      c = load_calibration_case(case_file, plan.readings ? &*plan.readings : nullptr, &calibrate_table, log);
    } catch (...) {
      log << "\n" << std::flush;  // the error's line (`workbench: error: ...`) starts a line of its own
      throw;
    }
    cases.push_back(std::move(c));
  }
  return cases;
}

/// Starts from the first case's own coefficients, and holds each case's own where not fitted,
/// unless the calibration file gives a start.
void start_from_first_case(CalibrationPlan& plan, const std::vector<CalibrationCase>& cases, const workbench::CaseFile& file) {
  for (std::size_t i = 0; i < kCoefficientCount; ++i) {
    if (plan.start_given[i]) continue;
    auto& p = plan.options.parameters[i];
    p.start = agent::kCoefficients[i].get(cases.front().study.coefficients);
    plan.options.weights.held_from_case[i] = !p.free;
    if (p.free && (p.start < p.lo || p.start > p.hi))
      file.root().table("calibrate").table(p.name).fail(
          "start", "the first case's own value " + std::to_string(p.start) + " lies outside [min, max]: give a start");
  }
}

/// One fold of the cross-validation: the fit on all cases but one, and that one's score.
struct Fold {
  std::string held_out;
  double fitted_on_others, fitted_on_all, start;
  agent::Coefficients k;
  Score held_out_score;  ///< the case left out, scored with the others' fit: its error per field
  int dim;               ///< the held-out case's dimension
};

std::vector<Fold> cross_validate(const std::vector<CalibrationCase>& cases, const CalibrationOptions& o,
                                 const CalibrationResult& result, std::ostream& log) {
  std::vector<Fold> folds;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    std::vector<CalibrationCase> train;
    for (std::size_t j = 0; j < cases.size(); ++j)
      if (j != i) train.push_back(cases[j]);
    log << "calibrate: cross-validation " << i + 1 << "/" << cases.size() << ": fitting without " << cases[i].name
        << "\n" << std::flush;
    const auto fold = calibrate(train, o, nullptr);
    std::vector<Score> score;
    objective({cases[i]}, fold.best, o.rules, o.weights, &score);
    folds.push_back({cases[i].name, score[0].objective, result.after[i].objective, result.before[i].objective, fold.best,
                     score[0], cases[i].study.mesh.grid.dim});
  }
  return folds;
}

/// The warnings of one case: not solved, load balance lost, or too little of the load reaching a rigid face.
void add_warnings(const std::string& name, const Score& b, const Score& a, std::vector<std::string>& warnings) {
  for (const auto& [s, when] : {std::pair{&b, "start"}, {&a, "fitted"}})
    if (s->load_refused)
      warnings.push_back("calibrate: WARNING: " + name + ": the agent model cannot be solved with the " + when +
                         " coefficients (its errors are not reported)");
  if (a.equilibrium_dev > b.equilibrium_dev + kLoadTolerance)
    warnings.push_back("calibrate: WARNING: the fit loses the load balance in " + name +
                       ": |rigid reaction - applied| / applied " + std::to_string(b.equilibrium_dev) + " before, " +
                       std::to_string(a.equilibrium_dev) + " after (calibrate.keep_load = false)");
  if (a.equilibrium_dev > 0.1)
    warnings.push_back("calibrate: WARNING: " + name + ": the rigid reaction is " + std::to_string(a.reaction_share) +
                       " of the applied load after the fit");
}

/// The warnings of the fit, fitted cases then held-out ones, then the references that limit the judgement.
std::vector<std::string> fit_warnings(const std::vector<CalibrationCase>& cases, const std::vector<CalibrationCase>& held,
                                      const CalibrationResult& result) {
  std::vector<std::string> warnings;
  for (std::size_t i = 0; i < cases.size(); ++i) add_warnings(cases[i].name, result.before[i], result.after[i], warnings);
  for (const auto& h : result.held_out) add_warnings(h.name + " (held out)", h.before, h.after, warnings);
  for (const auto* list : {&cases, &held})
    for (const auto& c : *list)
      if (!c.reference_limits.empty()) warnings.push_back("calibrate: WARNING: " + c.name + ": " + c.reference_limits);
  return warnings;
}

/// The held-out cases scored with the start and the fitted coefficients (each keeps its own held
/// coefficients, as a fitted case does); no load-balance ceiling: they are scored, not fitted.
void score_held_out(const std::vector<CalibrationCase>& held, const CalibrationOptions& o, CalibrationResult& result) {
  if (held.empty()) return;
  // Every rank scores every held-out case (no collective): one thread each under MPI, as calibrate() runs.
  const int threads = fem_reference::mpi_size() > 1 ? 1 : o.threads > 0 ? o.threads : int(std::thread::hardware_concurrency());
  const CaseShare share{0, 1, std::max(1, threads)};
  std::vector<Score> before, after;
  objective(held, result.start, o.rules, o.weights, &before, share);
  objective(held, result.best, o.rules, o.weights, &after, share);
  for (std::size_t i = 0; i < held.size(); ++i)
    result.held_out.push_back({held[i].name, held[i].study.mesh.grid.dim, before[i], after[i]});
}

/// What a calibration found, for its reports.
struct Found {
  const CalibrationPlan& plan;
  const std::vector<CalibrationCase>& cases;
  const std::vector<CalibrationCase>& held;  ///< the held-out cases (scores in result.held_out)
  const CalibrationResult& result;
  std::vector<Fold> folds;
  std::vector<std::string> warnings;
  double seconds;
};

/// A row of report.txt's table of errors: field k of a case before and after the fit, and its weight.
void field_row(std::ostream& r, std::size_t k, const std::string& name, int dim, const Score& before,
               const Score& after, const ObjectiveWeights& w) {
  if (!kFields[k].in(dim)) return;  // not compared in the case's dimension
  auto error = [&](const Score& s) {  // "-": not solved
    std::ostringstream t;
    t << std::setprecision(4);
    if (s.load_refused) t << "-";
    else t << s.error[k];
    return t.str();
  };
  r << std::left << std::setw(14) << kFields[k].name << std::setw(28) << name << std::right << std::setw(12)
    << error(before) << std::setw(12) << error(after) << std::setw(8) << w.field[k] << "\n";
}

/// report.txt's errors per field (kFields) and case, fitted then held out, before and after the fit.
void errors_table(std::ostream& r, const std::vector<CalibrationCase>& cases, const CalibrationResult& result,
                  const ObjectiveWeights& w) {
  r << std::left << std::setw(14) << "field" << std::setw(28) << "case" << std::right << std::setw(12) << "before"
    << std::setw(12) << "after" << std::setw(8) << "weight" << "\n";
  for (std::size_t k = 0; k < kFieldCount; ++k)
    for (std::size_t i = 0; i < cases.size(); ++i)
      field_row(r, k, cases[i].name, cases[i].study.mesh.grid.dim, result.before[i], result.after[i], w);
  if (result.held_out.empty()) return;
  r << "\nheld out (scored with the start and the fitted coefficients, never fitted):\n";
  for (std::size_t k = 0; k < kFieldCount; ++k)
    for (const auto& h : result.held_out) field_row(r, k, h.name, h.dim, h.before, h.after, w);
}

/// report.txt: the objective, the fit, each field's error per case (fitted and held out) before and
/// after, the load balance, the sensitivity and the cross-validation.
std::string report_text(const workbench::CaseFile& file, const Found& found) {
  const auto& [plan, cases, held, result, folds, warnings, seconds] = found;
  const auto& o = plan.options;
  std::ostringstream r;
  r << std::setprecision(4);
  r << "Calibration of " << file.path().string() << " (" << (agent::rule_set_name(o.rules))
    << " rule set, " << o.starts << " starts, seed " << o.seed << ", " << result.evaluations << " evaluations, "
    << seconds << " s)\n\n";
  r << "objective: sum over cases of weight * (";
  for (std::size_t k = 0, n = 0; k < kFieldCount; ++k)
    if (o.weights.field[k] > 0) r << (n++ ? " + " : "") << o.weights.field[k] << " e(" << kFields[k].name << ")^2";
  r << "), e = relative L2 error over the " << (o.weights.lines ? "sample lines" : o.weights.far ? "far field" : "body")
    << "; the other fields are reported, not fitted\n\n";
  r << "start:  " << coefficient_row(result.start) << "  objective " << result.objective_start << "\n";
  r << "fitted: " << coefficient_row(result.best) << "  objective " << result.objective_best << "\n\n";
  errors_table(r, cases, result, o.weights);
  r << "\n" << std::left << std::setw(28) << "case" << std::right << std::setw(22) << "equilibrium_dev before"
    << std::setw(10) << "after" << std::setw(22) << "reaction share before" << std::setw(10) << "after" << std::setw(14)
    << "reach before" << std::setw(10) << "after" << "\n";
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto &b = result.before[i], &a = result.after[i];
    r << std::left << std::setw(28) << cases[i].name << std::right << std::setw(22) << b.equilibrium_dev
      << std::setw(10) << a.equilibrium_dev << std::setw(22) << b.reaction_share << std::setw(10) << a.reaction_share
      << std::setw(14) << b.reach << std::setw(10) << a.reach << "\n";
  }
  r << "load balance: " << (o.weights.keep_load ? "kept (calibrate.keep_load): no case may end with a larger "
                                                 "equilibrium_dev than at the start"
                                               : "not constrained (calibrate.keep_load = false)")
    << "\n";
  for (const auto& w : warnings) r << w << "\n";
  r << "\nsensitivity at the optimum (objective with the coefficient moved by 10 % of its range):\n";
  if (o.weights.keep_load)
    r << "(2e+30: the move is refused, it would lose load; with calibrate.keep_load = false it is scored)\n";
  for (const auto& s : result.sensitivity)
    r << "  " << std::left << std::setw(8) << s.name << std::right << " -: " << std::setw(10) << s.objective_minus
      << "  +: " << std::setw(10) << s.objective_plus << "  curvature " << std::setw(10) << s.curvature << "  "
      << (s.pinned ? "pinned down by the data" : "NOT pinned down: the data hardly constrain it") << "\n";
  r << "\nobjective reached from each start:";
  for (double f : result.start_objectives) r << " " << f;
  r << "\n";
  if (!folds.empty()) {
    r << "\ncross-validation (fit on the other cases, score the one left out):\n";
    for (const auto& f : folds) {
      r << "  " << std::left << std::setw(28) << f.held_out << std::right << " held out: " << std::setw(10)
        << f.fitted_on_others << "  fitted on all: " << std::setw(10) << f.fitted_on_all << "  start: " << std::setw(10)
        << f.start << "\n    held-out error per field:";
      for (std::size_t k = 0; k < kFieldCount; ++k)
        if (kFields[k].in(f.dim)) r << " " << kFields[k].name << " " << f.held_out_score.error[k];
      r << "\n";
    }
  } else if (plan.cross_validate) {
    r << "\ncross-validation: needs two or more cases\n";
  }
  return r.str();
}

/// The errors of a score per field of kFields compared in `dim` dimensions (null: not solved).
nlohmann::json field_errors(const Score& s, int dim) {
  nlohmann::json e = nlohmann::json::object();
  for (std::size_t k = 0; k < kFieldCount; ++k)
    if (kFields[k].in(dim)) e[kFields[k].name] = s.load_refused ? nlohmann::json() : nlohmann::json(s.error[k]);
  return e;
}

/// A case's entry of report.json (`cases` and `held_out`): its errors and load balance before and after.
nlohmann::json case_json(const Score& b, const Score& a, int dim) {
  return {{"before", field_errors(b, dim)},
          {"after", field_errors(a, dim)},
          {"reaction_share", {{"before", b.reaction_share}, {"after", a.reaction_share}}},
          {"equilibrium_dev", {{"before", b.equilibrium_dev}, {"after", a.equilibrium_dev}}},
          {"reach", {{"before", b.reach}, {"after", a.reach}}}};
}

nlohmann::json coefficients_json(const agent::Coefficients& k) {
  nlohmann::json j;
  for (const auto& [name, value] : agent_study::coefficient_values(k)) j[name] = value;
  return j;
}

/// The threshold that acts in a case (agent::kCoefficients' row whose value acts) and the gamma
/// it gives [N] at the start and at the fit: a case's own unless the calibration sets gamma.
nlohmann::json threshold_json(const CalibrationCase& c, const CalibrationResult& result, const ObjectiveWeights& w) {
  const double entering = agent_study::entering_load(c.study, 1.0);
  const auto start = for_case(result.start, c.study.coefficients, w.held_from_case);
  const auto fitted = for_case(result.best, c.study.coefficients, w.held_from_case);
  nlohmann::json t{{"start", start.gamma_for(entering)}, {"fitted", fitted.gamma_for(entering)}};
  for (const auto& k : agent::kCoefficients)
    if (k.acts && k.acts_in(fitted)) t["coefficient"] = k.name;
  return t;
}

/// report.json's lists of names: `coefficients_used`, the coefficients the rule set reads
/// (agent::kCoefficients) that the calibration sets, fitted or held at a start (the rest, gamma when
/// held, gamma_relative, directions, ..., are each case's own); `fields`, kFields compared in any
/// case's dimension, in its order.
void add_names(nlohmann::json& j, const Found& found) {
  const auto& o = found.plan.options;
  const auto gamma = std::size_t(agent::find_coefficient("gamma") - agent::kCoefficients.data());
  j["coefficients_used"] = nlohmann::json::array();
  for (std::size_t i = 0; i < kCoefficientCount; ++i)
    if (agent::kCoefficients[i].used_by(o.rules) && !(i == gamma && o.weights.held_from_case[i]))
      j["coefficients_used"].push_back(agent::kCoefficients[i].name);
  j["fields"] = nlohmann::json::array();
  auto in_any = [](const FieldSpec& f, const std::vector<CalibrationCase>& list) {
    return std::any_of(list.begin(), list.end(), [&](const CalibrationCase& c) { return f.in(c.study.mesh.grid.dim); });
  };
  for (const auto& f : kFields)
    if (in_any(f, found.cases) || in_any(f, found.held)) j["fields"].push_back(f.name);
}

/// report.json: what report.txt says, as data.
nlohmann::json report_json(const workbench::CaseFile& file, const Found& found) {
  const auto& [plan, cases, held, result, folds, warnings, seconds] = found;
  const auto& o = plan.options;
  nlohmann::json j;
  j["calibration"] = file.path().string();
  j["title"] = file.root().text("title", "");
  j["rule_set"] = agent::rule_set_name(o.rules);
  j["scope"] = o.weights.lines ? "lines" : o.weights.far ? "far" : "body";  // where the errors are measured
  if (plan.readings) j["readings"] = agent_study::names_of(*plan.readings);
  add_names(j, found);
  j["start"] = coefficients_json(result.start);
  j["fitted"] = coefficients_json(result.best);
  j["objective"] = {{"start", result.objective_start}, {"fitted", result.objective_best}};
  j["evaluations"] = result.evaluations;
  j["seconds"] = seconds;
  j["start_objectives"] = result.start_objectives;
  for (std::size_t k = 0; k < kFieldCount; ++k) j["weights"][kFields[k].name] = o.weights.field[k];
  for (std::size_t i = 0; i < cases.size(); ++i) {
    j["cases"][cases[i].name] = case_json(result.before[i], result.after[i], cases[i].study.mesh.grid.dim);
    j["cases"][cases[i].name]["threshold"] = threshold_json(cases[i], result, o.weights);
    j["cases"][cases[i].name]["reference"] = cases[i].reference_level;
  }
  for (std::size_t i = 0; i < held.size(); ++i) {
    const auto& h = result.held_out[i];
    j["held_out"][h.name] = case_json(h.before, h.after, h.dim);
    j["held_out"][h.name]["threshold"] = threshold_json(held[i], result, o.weights);
    j["held_out"][h.name]["reference"] = held[i].reference_level;
  }
  j["keep_load"] = o.weights.keep_load;
  j["warnings"] = warnings;
  for (const auto& s : result.sensitivity)
    j["sensitivity"][s.name] = {{"minus", s.objective_minus}, {"plus", s.objective_plus}, {"curvature", s.curvature}, {"pinned", s.pinned}};
  for (const auto& f : folds)
    j["cross_validation"][f.held_out] = {{"held_out", f.fitted_on_others}, {"fitted_on_all", f.fitted_on_all},
                                         {"start", f.start}, {"held_out_errors", field_errors(f.held_out_score, f.dim)}};
  return j;
}

/// calibrated/<case>.toml for every case, fitted and held out: its own file with the fitted coefficients.
void write_calibrated_cases(const workbench::CaseFile& file, const CalibrationPlan& plan, const CalibrationResult& result,
                            const std::vector<CalibrationCase>& cases, const std::vector<CalibrationCase>& held,
                            const fs::path& dir) {
  fs::create_directories(dir / "calibrated");
  const std::string note = "Calibrated by `workbench calibrate " + file.path().string() + "`: objective " +
                           std::to_string(result.objective_start) + " -> " + std::to_string(result.objective_best);
  const auto& o = plan.options;
  auto write = [&](const fs::path& original, const CalibrationCase& c, const std::string& what) {
    write_calibrated_case(original, dir / "calibrated" / (c.name + ".toml"),
                          for_case(result.best, c.study.coefficients, o.weights.held_from_case), o.rules, plan.readings,
                          note + what);
  };
  for (std::size_t i = 0; i < cases.size(); ++i) write(plan.case_files[i], cases[i], "");
  for (std::size_t i = 0; i < held.size(); ++i) write(plan.held_out_files[i], held[i], " (this case held out: scored, not fitted)");
}

}  // namespace

CalibrationResult run_calibration(const workbench::CaseFile& file, const fs::path& dir, std::ostream& log) {
  const auto start_time = std::chrono::steady_clock::now();
  CalibrationPlan plan;
  std::vector<CalibrationCase> cases, held;
  fem_reference::mpi_collective([&] {
    plan = read_calibration_plan(file);
    file.reject_unknown_keys();
    const auto case_files = open_cases(plan.case_files), held_files = open_cases(plan.held_out_files);
    cases = load_cases(file, plan, case_files, "case", log);
    held = load_cases(file, plan, held_files, "held-out case", log);
  });
  for (std::size_t i = 0; i < cases.size(); ++i) cases[i].weight = plan.case_weights[i];
  start_from_first_case(plan, cases, file);
  const auto& o = plan.options;
  log << "calibrate: fitting with " << o.starts << " starts (seed " << o.seed << ")\n" << std::flush;
  auto result = calibrate(cases, o, &log);
  Found found{plan, cases, held, result, {}, {}, 0};
  // Cross-validation: fit on all cases but one, score the one left out.
  if (plan.cross_validate && cases.size() >= 2) found.folds = cross_validate(cases, o, result, log);
  score_held_out(held, o, result);
  found.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  found.warnings = fit_warnings(cases, held, result);
  const std::string report = report_text(file, found);
  // The files, written once (rank 0 under MPI).
  fem_reference::mpi_on_root([&] {
    report::write_text(dir / "report.txt", report);
    log << report;
    report::write_text(dir / "report.json", report_json(file, found).dump(2) + "\n");
    write_calibrated_cases(file, plan, result, cases, held, dir);
    report::render_html(dir, log);
  });
  return result;
}

}  // namespace compare

// What both comparisons share: the gate, summary.json / summary.txt / junit.xml, the FEM run and the figure script.
#include "report.h"

#include <fem_reference/fem_case.h>
#include <fem_reference/mpi.h>
#include <workbench/child_process.h>
#include <workbench/csv_file.h>
#include <workbench/error.h>
#include <workbench/output_file.h>
#include <workbench/staged_directory.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace compare::report {

namespace fs = std::filesystem;
using workbench::Error;

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void write_text(const fs::path& file, const std::string& text) { workbench::write_file(file, text); }

namespace {

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

}  // namespace

namespace {
bool is_rel_l2(const std::string& name) {
  const std::string suffix = ".rel_l2";
  return name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
}
bool is_rel_l2(const Metric& m) { return is_rel_l2(m.name); }
}  // namespace

void check_gate_names(const CompareOptions& options, const std::vector<std::string>& names,
                      const workbench::CaseTable& root) {
  for (const auto& [name, limit] : options.gate)
    if (std::find(names.begin(), names.end(), name) == names.end())
      root.table("compare").fail("gate." + name, "unknown metric for model \"" + options.model +
                                                     "\" (docs/compare.md lists them)");
  for (const auto& field : options.better_than_zero)
    if (std::find(names.begin(), names.end(), field + ".rel_l2") == names.end())
      root.table("compare").fail("better_than_zero", "\"" + field + "\" is no compared field (a scope and a field, "
                                                     "e.g. \"far.sigma_x\"; docs/compare.md lists them)");
  // A relative L2 limit at or above the zero model's would pass a model that predicts nothing.
  for (const auto& [name, limit] : options.gate) {
    if (limit < kZeroModelRelL2 || !is_rel_l2(name)) continue;
    const std::string field = name.substr(0, name.size() - std::strlen(".rel_l2"));
    const auto& required = options.better_than_zero;
    if (std::find(required.begin(), required.end(), field) == required.end())
      root.table("compare").fail("gate." + name, "a limit of " + workbench::shortest_decimal(limit) +
                                                     " passes a model that predicts nothing (predicting zero scores 1): "
                                                     "set it below 1, or add \"" + field + "\" to better_than_zero");
  }
}

namespace {

/// The reference does not resolve the field in this scope (its own error >= kUnresolvedReferenceError).
bool unresolved(const Metric& m) {
  return is_rel_l2(m) && std::isfinite(m.reference_error) && m.reference_error >= kUnresolvedReferenceError;
}

/// Flagged "worse than zero" in the summaries: a resolved field the model predicts no better than 0
/// (a component the rule set does not model is not its error).
bool flagged_worse(const Metric& m) { return m.modelled && worse_than_zero(m) && !unresolved(m); }

/// The field of a metric's name ("far.sigma_y.rel_l2": "sigma_y"; a line's scope too).
std::string field_of(const std::string& name) {
  const auto last = name.rfind('.'), before = name.rfind('.', last - 1);
  return name.substr(before + 1, last - before - 1);
}

}  // namespace

bool worse_than_zero(const Metric& m) { return is_rel_l2(m) && !(m.value < kZeroModelRelL2); }

fem_reference::FemResult run_fem(const fem_reference::FemProblem& problem, const std::filesystem::path& dir,
                                 std::ostream& log, double& seconds) {
  const auto start = std::chrono::steady_clock::now();
  // Every rank writes its VTU piece into dir/fem; rank 0 makes the folder and writes the CSV files.
  fem_reference::mpi_on_root([&] { std::filesystem::create_directories(dir / "fem"); });
  auto fem = fem_reference::solve_fem(problem, dir / "fem", &log);
  fem_reference::mpi_on_root([&] { fem_reference::write_fem_csv(fem, dir / "fem"); });
  seconds = seconds_since(start);
  return fem;
}

double fem_equilibrium_dev(const fem_reference::FemResult& fem) {
  double reaction[3] = {0, 0, 0};
  for (const auto& r : fem.reactions)
    for (int a = 0; a < 3; ++a) reaction[a] += r.force[a];
  double imbalance = 0, applied = 0;
  for (int a = 0; a < 3; ++a) {
    imbalance += std::pow(reaction[a] + fem.applied[a], 2);
    applied += std::pow(fem.applied[a], 2);
  }
  return std::sqrt(imbalance / applied);
}

namespace {

/// junit.xml: one test case per gated metric, a <failure> for each one over its limit, <skipped>
/// for a metric of a component the rule set does not model.
void write_junit(const fs::path& file, const std::string& case_name, const std::map<std::string, double>& gate,
                 const std::vector<std::string>& better_than_zero, const CompareOutcome& outcome) {
  std::ostringstream junit;
  junit.precision(12);
  // a gated metric of a component the rule set does not model is a skipped test case
  std::size_t skipped = 0;
  for (const auto& m : outcome.metrics)
    if (!m.modelled)
      skipped += gate.count(m.name) + (is_rel_l2(m) ? std::size_t(std::count(better_than_zero.begin(), better_than_zero.end(),
                                                                              m.name.substr(0, m.name.size() - 7)))
                                                    : 0);
  junit << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n  <testsuite name=\"compare."
        << xml_escape(case_name) << "\" tests=\"" << outcome.gated + skipped << "\" failures=\"" << outcome.failures.size()
        << (skipped ? "\" skipped=\"" + std::to_string(skipped) : std::string()) << "\">\n";
  for (const auto& [name, limit] : gate) {
    const auto m = std::find_if(outcome.metrics.begin(), outcome.metrics.end(), [&](const Metric& x) { return x.name == name; });
    if (m == outcome.metrics.end()) throw Error("compare: gated metric " + name + " was not computed");
    junit << "    <testcase classname=\"compare\" name=\"" << xml_escape(name) << "\">";
    if (!m->modelled)
      junit << "<skipped message=\"not modelled by the rule set\"/>";
    else if (!(m->value <= limit))
      junit << "<failure message=\"" << xml_escape(name) << " = " << m->value << " exceeds " << limit << " by "
            << m->value - limit << "\"/>";
    junit << "</testcase>\n";
  }
  for (const auto& field : better_than_zero) {
    const auto m = std::find_if(outcome.metrics.begin(), outcome.metrics.end(),
                                [&](const Metric& x) { return x.name == field + ".rel_l2"; });
    junit << "    <testcase classname=\"compare\" name=\"" << xml_escape(field) << ".better_than_zero\">";
    if (!m->modelled)
      junit << "<skipped message=\"not modelled by the rule set\"/>";
    else if (worse_than_zero(*m))
      junit << "<failure message=\"" << xml_escape(m->name) << " = " << m->value
            << " is not below the zero model's " << kZeroModelRelL2 << ": worse than predicting zero\"/>";
    junit << "</testcase>\n";
  }
  for (const auto& f : outcome.failures)
    if (!f.refused.empty())
      junit << "    <testcase classname=\"compare\" name=\"carry_check\"><failure message=\"" << xml_escape(f.describe())
            << "\"/></testcase>\n";
  junit << "  </testsuite>\n</testsuites>\n";
  write_text(file, junit.str());
}

}  // namespace

void finish(const fs::path& dir, const fs::path& case_file, nlohmann::json json,
            const std::map<std::string, double>& gate, const std::vector<std::string>& notes, CompareOutcome& outcome,
            std::ostream& log, const std::vector<std::string>& better_than_zero, BackgroundFigures* figures) {
  const std::string case_name = case_file.stem().string();
  // Nothing non-finite is written with exit 0: a metric that is not a number is an error (a zero
  // reference norm, a non-finite field), named with the metric, before any summary is written.
  for (const auto& m : outcome.metrics)
    if (!std::isfinite(m.value))
      throw Error(case_file.string() + ": compare: metric " + m.name + " is " + std::to_string(m.value) + " (" + m.meaning +
                  "): not a finite number, nothing written");
  // The gate.
  outcome.gated = 0;
  outcome.failures.clear();
  for (const auto& m : outcome.metrics) {
    auto it = gate.find(m.name);
    if (it == gate.end() || !m.modelled) continue;  // a component the rule set does not model is not gated
    ++outcome.gated;
    if (!(m.value <= it->second)) outcome.failures.push_back({m.name, m.value, it->second, false, {}});
  }
  for (const auto& field : better_than_zero) {
    const auto m = std::find_if(outcome.metrics.begin(), outcome.metrics.end(),
                                [&](const Metric& x) { return x.name == field + ".rel_l2"; });
    if (m == outcome.metrics.end()) throw Error("compare: field " + field + " was not compared");
    if (!m->modelled) continue;
    ++outcome.gated;
    if (worse_than_zero(*m)) outcome.failures.push_back({m->name, m->value, kZeroModelRelL2, true, {}});
  }
  // A load the rule set cannot carry fails a gate with the carry check's line, not with its errors alone.
  if (!gate.empty() || !better_than_zero.empty())
    for (const auto& r : outcome.refused) {
      ++outcome.gated;
      outcome.failures.push_back({"carry_check", 0.0, 0.0, false, r});
    }
  // A field the model predicts no better than zero is said so, in the body and the far field.
  // A field the reference does not resolve in a scope is not judged, and the summary says which.
  std::string worse, not_judged, not_modelled;
  for (const auto& m : outcome.metrics) {
    if (!m.modelled && is_rel_l2(m) && m.name.rfind("far.", 0) == 0) not_modelled += (not_modelled.empty() ? "" : ", ") + field_of(m.name);
    if (flagged_worse(m) && (m.name.rfind("body.", 0) == 0 || m.name.rfind("far.", 0) == 0))
      worse += (worse.empty() ? "" : ", ") + m.name.substr(0, m.name.size() - 7);
    if (unresolved(m)) not_judged += (not_judged.empty() ? "" : ", ") + m.name.substr(0, m.name.size() - 7);
  }
  if (!worse.empty())
    outcome.warnings.push_back("worse than predicting zero (relative L2 error >= 1, the zero model's): " + worse);
  std::vector<std::string> all_notes = notes;
  if (!not_modelled.empty())
    all_notes.push_back("not modelled by the rule set (written as 0; scored, but not judged against the zero model "
                        "nor gated): " + not_modelled);
  if (!not_judged.empty())
    all_notes.push_back("not judged against the zero model (the reference's own error >= " +
                        [] { std::ostringstream v; v << kUnresolvedReferenceError; return v.str(); }() +
                        ": FEM does not resolve the field there, e.g. zero by symmetry): " + not_judged);

  // Summary: JSON for programs, a table for people, JUnit XML for CI systems.
  for (const auto& m : outcome.metrics) {
    nlohmann::json entry{{"value", m.value}, {"meaning", m.meaning}};
    if (std::isfinite(m.reference_error)) entry["reference_error"] = m.reference_error;
    if (std::isfinite(m.staircase_error)) entry["staircase_error"] = m.staircase_error;
    if (std::isfinite(m.agents_only)) entry["agents_only"] = m.agents_only;
    if (!m.modelled) entry["modelled"] = false;
    if (m.name.size() > 7 && m.name.compare(m.name.size() - 7, 7, ".rel_l2") == 0) {
      entry["zero_model"] = kZeroModelRelL2;
      entry["worse_than_zero"] = flagged_worse(m);
      if (std::isfinite(m.reference_error)) entry["resolved"] = !unresolved(m);
    }
    if (auto it = gate.find(m.name); it != gate.end()) {
      entry["limit"] = it->second;
      if (m.modelled) entry["passed"] = m.value <= it->second;
    }
    json["metrics"][m.name] = entry;
  }
  json["unresolved_reference_error"] = kUnresolvedReferenceError;  // a metric is "resolved" below it
  json["gate"] = {{"checked", outcome.gated}, {"failed", outcome.failures.size()}};
  for (const auto& f : outcome.failures)
    if (!f.refused.empty()) json["gate"]["refused"].push_back(f.describe());
  json["warnings"] = outcome.warnings;
  write_text(dir / "summary.json", json.dump(2) + "\n");

  std::ostringstream table;
  for (const auto& w : outcome.warnings) table << "WARNING: " << w << "\n";
  for (const auto& n : all_notes) table << n << "\n";
  if (!all_notes.empty() || !outcome.warnings.empty()) table << "\n";
  std::size_t width = 40;
  for (const auto& m : outcome.metrics) width = std::max(width, m.name.size() + 2);
  table << std::left << std::setw(int(width)) << "metric" << std::right << std::setw(14) << "value" << std::setw(16)
        << "reference_error" << std::setw(12) << "limit\n";
  for (const auto& m : outcome.metrics) {
    table << std::left << std::setw(int(width)) << m.name << std::right << std::setw(14) << std::setprecision(5)
          << m.value << std::setw(16);
    if (std::isfinite(m.reference_error)) table << m.reference_error;
    else table << "";
    if (auto it = gate.find(m.name); it != gate.end())
      table << std::setw(12) << it->second << (!m.modelled ? "  not gated" : m.value <= it->second ? "  ok" : "  EXCEEDED");
    if (std::isfinite(m.staircase_error)) table << "  staircase_error " << m.staircase_error;
    if (std::isfinite(m.agents_only)) table << "  agents_only " << m.agents_only;
    if (!m.modelled) table << "  NOT MODELLED";
    if (flagged_worse(m)) table << "  WORSE THAN ZERO";
    if (unresolved(m)) table << "  NOT RESOLVED BY THE REFERENCE";
    table << "\n";
  }
  write_text(dir / "summary.txt", table.str());
  log << table.str();

  write_junit(dir / "junit.xml", case_name, gate, better_than_zero, outcome);
  if (figures) figures->render_report(log);
  else render_html(dir, log);
}

void render_html(const fs::path& dir, std::ostream& log) {
  log << "report: writing report.html\n" << std::flush;
  workbench::run_python_script("compare/report_html.py", {dir.string()}, dir / "report.log", "report_html.py");
}

namespace {
/// The scripts' --formats argument: "png,pdf".
std::string format_list(const std::vector<std::string>& formats) {
  std::string list;
  for (const auto& f : formats) list += (list.empty() ? "" : ",") + f;
  return list;
}
}  // namespace

void run_figure_script(const std::string& script, const fs::path& dir, const std::string& title,
                       const std::vector<std::string>& formats, std::ostream& log) {
  const std::string name = fs::path(script).filename().string();
  log << "compare: drawing figures (" << name << ")\n" << std::flush;
  workbench::run_python_script(script, {dir.string(), "--title", title, "--formats", format_list(formats)},
                               dir / "figures.log", name);
}

BackgroundFigures::BackgroundFigures(const fs::path& dir, const std::vector<std::string>& formats, std::ostream& log)
    : log_file_(dir / "figures.log"),
      child_(workbench::python_script_command("compare/figures.py",
                                              {dir.string(), "--formats", format_list(formats), "--wait", "--report"}),
             log_file_),
      report_log_(dir / "report.log") {
  log << "compare: drawing figures (figures.py) beside the FEM reference\n" << std::flush;
}

void BackgroundFigures::title(std::string text) {
  std::replace_if(text.begin(), text.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  child_.send("title " + text);  // a script that already ended says why in drawn()
}

void BackgroundFigures::steps_ready() {
  child_.send("steps");  // a script that already ended says why in finish()
}

void BackgroundFigures::data_ready() {
  child_.send("draw");  // a script that already ended says why in finish()
}

void BackgroundFigures::drawn() {
  if (child_.receive() == "drawn") return;
  // It ended (or wrote back a failed write's message): its status and last line say why.
  workbench::check_script_status(child_.wait(), log_file_, "figures.py", child_.report());
  throw workbench::Error("figures.py ended before it had drawn the figures (see " +
                         workbench::shown_text(log_file_.string()) + ")");
}

void BackgroundFigures::render_report(std::ostream& log) {
  log << "report: writing report.html\n" << std::flush;
  child_.send("report");  // a script that already ended says why below
  workbench::check_script_status(child_.wait(), report_log_, "report_html.py", child_.report());
}

}  // namespace compare::report

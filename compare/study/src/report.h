#pragma once
// What every comparison (agent against FEM, PBD against FEM) shares: checking the gate's metric
// names, the gate itself, summary.json / summary.txt / junit.xml, the figure script, timing and
// FEM equilibrium. Private to the compare library.
#include <compare/compare_study.h>
#include <fem_reference/fem.h>
#include <workbench/case_file.h>
#include <workbench/child_process.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace compare {

/// The metrics of the PBD comparison (pbd_compare.cc), for metric_names.
std::vector<std::string> pbd_metric_names();

}  // namespace compare

namespace compare::report {

class BackgroundFigures;

double seconds_since(std::chrono::steady_clock::time_point t);

/// Writes `text` to `file` (JSON, text, XML; CSV tables go through workbench::CsvFile); throws
/// workbench::Error if it cannot be opened or written.
void write_text(const std::filesystem::path& file, const std::string& text);

/// Rejects (case-file error naming compare.gate.<name>) a gate key that is not in `names`.
void check_gate_names(const CompareOptions& options, const std::vector<std::string>& names,
                      const workbench::CaseTable& root);

/// Solves the FEM reference with its VTU and CSV output in dir/fem; `seconds` gets the time.
fem_reference::FemResult run_fem(const fem_reference::FemProblem& problem, const std::filesystem::path& dir,
                                 std::ostream& log, double& seconds);

/// |sum of reactions + applied| / |applied| of a FEM solution.
double fem_equilibrium_dev(const fem_reference::FemResult& fem);

/// Applies the gate (limits, and the fields `better_than_zero` must name whose relative L2 error
/// must be below the zero model's) to `outcome.metrics` (fills failures and gated; a warning names
/// every body and far-field error that is worse than zero) and writes summary.json
/// (`header` plus every metric with meaning, limit and verdict, and the gate's counts),
/// summary.txt (`notes`, then the metric table, also on `log`) and junit.xml (one test case per
/// gated metric, a <failure> for each one over its limit) into `dir`, then report.html: by
/// `figures` when they were drawn beside the study (BackgroundFigures::render_report), else by
/// render_html. A metric that is not finite is a workbench::Error naming it and `case_file`, before
/// anything is written.
void finish(const std::filesystem::path& dir, const std::filesystem::path& case_file, nlohmann::json header,
            const std::map<std::string, double>& gate, const std::vector<std::string>& notes, CompareOutcome& outcome,
            std::ostream& log, const std::vector<std::string>& better_than_zero = {},
            BackgroundFigures* figures = nullptr);

/// Whether `m` is a relative L2 error not below the zero model's (kZeroModelRelL2): the model
/// does no better than predicting zero there. The gate's test (`better_than_zero`); the summaries
/// flag it only where the reference resolves the field (its own error below kUnresolvedReferenceError).
bool worse_than_zero(const Metric& m);

/// Renders dir/report.html from summary.json (a comparison) or report.json (a calibration) and the
/// figures beside it with compare/report_html.py (Jinja2; its output into dir/report.log), once
/// everything else is written; throws workbench::Error with the script's last line when it fails,
/// so that a study without its page is a failed study.
void render_html(const std::filesystem::path& dir, std::ostream& log);

/// Runs `python <script> <dir> --title <title> --formats <png,pdf>` (`script` relative to share/workbench/, e.g.
/// "compare/figures.py"; workbench/child_process.h), output into dir/figures.log; throws
/// workbench::Error with its last line when it fails.
void run_figure_script(const std::string& script, const std::filesystem::path& dir, const std::string& title,
                       const std::vector<std::string>& formats, std::ostream& log);

/// compare/figures.py drawing beside the comparison (`--wait --report`): started before the case's
/// mesh is read, it loads matplotlib, takes the title (title()), waits for steps_ready()
/// (steps.csv, lines.json, agent/ written) and draws the load-step animation while the FEM
/// reference solves, then waits for data_ready() (lines.csv, cells.csv, nodes.csv complete) and
/// draws Figures 8-11 while the reference's error estimate solves; once the summaries are written
/// it renders report.html in the same process (render_report). Destroyed before that (an error in
/// between), it ends the script.
class BackgroundFigures {
 public:
  BackgroundFigures(const std::filesystem::path& dir, const std::vector<std::string>& formats, std::ostream& log);
  /// The figures' title (one line: a line break in it becomes a space).
  void title(std::string text);
  /// steps.csv and lines.json are complete: the animation can be drawn.
  void steps_ready();
  /// The files the figures need besides the agent's are complete.
  void data_ready();
  /// Waits until the figures are written (the script says "drawn"); throws workbench::Error with
  /// its last line when it failed.
  void drawn();
  /// Has the script render report.html (summary.json written) and waits for it to end; throws
  /// workbench::Error with the renderer's last line (report.log) when it failed.
  void render_report(std::ostream& log);

 private:
  std::filesystem::path log_file_;
  workbench::ChildProcess child_;
  std::filesystem::path report_log_;  // the renderer's output (render_report)
};

}  // namespace compare::report

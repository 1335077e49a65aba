#pragma once
// One study, two models: a fast model and the FEM reference from one case file (docs/compare.md).
// [compare] model = "agent" (default): the agent method and FEM on the identical gmsh mesh,
// compared cell by cell and along sample lines. model = "pbd": the PBD angle bending rod
// ([pbd]) against the FEM strip (the shared sections), compared along the centreline and with
// Euler-Bernoulli.
#include <compare/metrics.h>
#include <compare/reference.h>
#include <workbench/case_file.h>

#include <filesystem>
#include <iosfwd>
#include <array>
#include <limits>
#include <map>
#include <utility>
#include <string>
#include <vector>

namespace compare {

/// A named number of the summary (errors, ratios, equilibrium, timings).
struct Metric {
  std::string name;
  double value;
  std::string meaning;
  /// The same error of the reference's second level against the reference (docs/compare.md):
  /// how much of `value` may be the reference's own discretisation error. NaN: not an error norm.
  double reference_error = std::numeric_limits<double>::quiet_NaN();
  /// Beside a reference on the true geometry ([compare.reference] mesh): the same error of FEM on
  /// the agents' own staircase mesh against it, the staircase's own share. NaN otherwise.
  double staircase_error = std::numeric_limits<double>::quiet_NaN();
  /// Where the agents' fields include a closed-form layer (agent::StressModel::closed_forms): the
  /// same error of the agents alone (agent.closed_forms = "left_out") against the reference. NaN otherwise.
  double agents_only = std::numeric_limits<double>::quiet_NaN();
  /// False for a metric of a stress component the rule set does not model (agent::StressModel):
  /// scored, but neither flagged worse than zero nor gated (docs/compare.md, "Not modelled").
  bool modelled = true;
};

/// The names of the metrics a study with these options produces (for checking the gate's keys):
/// the agent model's for its scopes (body, far and the names of its sample lines) and the fields
/// of compare::kFields compared in `dim` dimensions, or the PBD comparison's.
std::vector<std::string> metric_names(const CompareOptions& options, const std::vector<std::string>& line_names, int dim);

struct GateFailure {
  std::string metric;
  double value, limit;
  bool zero_model = false;  ///< the limit is the zero model's error (compare.better_than_zero)
  /// Not a metric: the carry check refused a load (agent_study::carry_check); the line says which and why.
  std::string refused;
  /// One line: "far.sigma_x.rel_l2 = 1.6 exceeds 0.5 by 1.1", or "... is not below the zero model's 1:
  /// worse than predicting zero".
  std::string describe() const;
};

/// Columns of one table of compared fields, rows in the order of the CSV file the study wrote
/// beside them (cells.csv, nodes.csv, lines.csv, centreline.csv), for callers that want them in
/// memory (the Python module) rather than read back from the files.
struct FieldTable {
  enum class Kind { Real, Flag, Integer };
  struct Column {
    std::string name;
    int components = 1;
    std::vector<double> values;  ///< rows x components, row-major; a flag is 0 or 1
    Kind kind = Kind::Real;
  };
  std::size_t rows = 0;
  std::vector<Column> columns;
  /// Appends a column of rows x components values.
  void add(const std::string& name, int components, std::vector<double> values, Kind kind = Kind::Real);
};

/// The fields a comparison compared. Agent: cells (per agent, cells.csv's order), nodes (the
/// body's nodes, nodes.csv's order), one table per sample line (lines.csv); PBD: the centreline.
struct ComparedFields {
  FieldTable cells, nodes;
  std::vector<std::pair<std::string, FieldTable>> lines;  ///< line name, its samples
};

struct CompareOutcome {
  std::vector<Metric> metrics;
  ComparedFields fields;
  std::vector<GateFailure> failures;  ///< gated metrics over their limit
  std::size_t gated = 0;              ///< metrics the gate checks
  std::vector<std::string> warnings;  ///< said on the log and in the summary (e.g. load lost)
  /// Loads the rule set cannot carry (the carry check before the run), one line each: each fails
  /// a case's gate (when it has one) with that line.
  std::vector<std::string> refused;
};

/// Runs both models from the case file, compares them and writes everything into `dir`. Agent:
/// agent/, fem/, compare.vtu, cells.csv, lines.csv, nodes.csv, steps.csv; PBD: pbd/, fem/,
/// centreline.csv; both: summary.json, summary.txt, junit.xml, figures/. Rejects unknown keys (and
/// gate keys naming no metric of the chosen model) before running anything.
CompareOutcome run_compare(const workbench::CaseFile& file, const std::filesystem::path& dir, std::ostream& log);

/// What run_compare reads and checks before it runs anything, without running it (`--check`):
/// the case, the fast model's mesh, the FEM strip's (PBD) or the same-body check (agents). Every
/// rank, each step collective. Returns the warnings the run would give before it runs (the body's
/// size, the load patches).
std::vector<std::string> check_compare(const workbench::CaseFile& file);

}  // namespace compare

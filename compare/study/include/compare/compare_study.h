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
#include <string>
#include <vector>

namespace compare {

/// The [compare] table of a case file.
struct CompareOptions {
  std::string model = "agent";                  ///< the fast model: "agent" or "pbd"
  std::vector<double> depths{0.25, 0.5, 0.75};  ///< agent: lines across each load, fractions of the body along it
  double mask = 0.01;                           ///< agent: ratio masked where |FEM| < mask * max |FEM|
  ReferenceOptions reference;                   ///< agent: [compare.reference]
  /// agent: the far field leaves out cells closer than this to a loaded face [m]; 0: 5 agent sizes
  double far_distance = 0;
  /// agent: the warning when the agent model carries less than this share of the load to a rigid face
  double min_reaction_share = 0.9;
  std::vector<std::array<Eigen::Vector3d, 2>> lines;  ///< agent: [[compare.line]] from, to [m]
  std::map<std::string, double> gate;           ///< metric name -> largest value allowed
  bool figures = true;                          ///< Figures 8-11 and the animation (Python)
  /// The figures' files: "png" (quick to draw and view), "pdf" (vector, for print; about 1 s more
  /// CPU on the seed plate, docs/performance.md).
  std::vector<std::string> figure_formats{"png"};
};

/// Reads [compare]: model, then the keys that model uses (depths, mask, reference, far field and
/// lines for the agent model only), figures, gate.
CompareOptions read_compare_options(const workbench::CaseTable& root);

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
};

/// The names of the metrics a study with these options produces (for checking the gate's keys):
/// the agent model's for its scopes (body, far and the names of its sample lines), or the PBD
/// comparison's.
std::vector<std::string> metric_names(const CompareOptions& options, const std::vector<std::string>& line_names);

struct GateFailure {
  std::string metric;
  double value, limit;
};

struct CompareOutcome {
  std::vector<Metric> metrics;
  std::vector<GateFailure> failures;  ///< gated metrics over their limit
  std::size_t gated = 0;              ///< metrics the gate checks
  std::vector<std::string> warnings;  ///< said on the log and in the summary (e.g. load lost)
};

/// Runs both models from the case file, compares them and writes everything into `dir`. Agent:
/// agent/, fem/, compare.vtu, cells.csv, lines.csv, nodes.csv, steps.csv; PBD: pbd/, fem/,
/// centreline.csv; both: summary.json, summary.txt, junit.xml, figures/. Rejects unknown keys (and
/// gate keys naming no metric of the chosen model) before running anything.
CompareOutcome run_compare(const workbench::CaseFile& file, const std::filesystem::path& dir, std::ostream& log);

}  // namespace compare

#pragma once
// One study, two models: the agent method and the FEM reference on the identical gmsh mesh,
// compared cell by cell and along sample lines (issue 4, docs/compare.md).
#include <compare/metrics.h>
#include <workbench/case_file.h>

#include <filesystem>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace compare {

/// The [compare] table of a case file.
struct CompareOptions {
  std::vector<double> depths{0.25, 0.5, 0.75};  ///< horizontal lines, fractions of the height below the top
  double mask = 0.01;                           ///< ratio masked where |FEM| < mask * max |FEM|
  std::map<std::string, double> gate;           ///< metric name -> largest value allowed
  bool figures = true;                          ///< Figures 8-11 and the animation (Python)
};

CompareOptions read_compare_options(const workbench::CaseTable& root);

/// A named number of the summary (errors, ratios, equilibrium, timings).
struct Metric {
  std::string name;
  double value;
  std::string meaning;
};

/// The names of the metrics a study with these lines produces (for checking the gate's keys).
std::vector<std::string> metric_names(const std::vector<double>& depths);

struct GateFailure {
  std::string metric;
  double value, limit;
};

struct CompareOutcome {
  std::vector<Metric> metrics;
  std::vector<GateFailure> failures;  ///< gated metrics over their limit
  std::size_t gated = 0;              ///< metrics the gate checks
};

/// Runs both models from the case file, compares them and writes everything into `dir`
/// (agent/, fem/, compare.vtu, cells.csv, lines.csv, nodes.csv, steps.csv, summary.json,
/// summary.txt, junit.xml, figures/). Rejects unknown keys before running anything.
CompareOutcome run_compare(const workbench::CaseFile& file, const std::filesystem::path& dir, std::ostream& log);

}  // namespace compare

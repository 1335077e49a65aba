#pragma once
// `workbench summarize`: the summaries of many output folders as one table, one row per folder.
//
//   const auto table = compare::summarize({"out/a/compare", "out/b/compare"});
//   compare::write_summary_csv(table, "out/sweep.csv", false);
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace compare {

/// One output folder: the case keys its study was run with and the numbers its summary gives.
struct SummaryRow {
  std::string folder;                            ///< as given
  std::map<std::string, std::string> parameters; ///< dotted case key -> value (strings unquoted)
  std::map<std::string, double> metrics;         ///< name -> number
  /// The metrics of components the rule set does not model (summary.json's `"modelled": false`:
  /// written as 0, scored, not judged), sorted; their numbers are in `metrics` as summary.json gives them.
  std::vector<std::string> not_modelled;
};

struct SummaryTable {
  std::vector<std::string> parameters;  ///< the case keys whose values differ between the rows, sorted
  std::vector<std::string> metrics;     ///< every number any row has, sorted
  std::vector<SummaryRow> rows;         ///< one per folder, in the order given
};

/// Reads each folder's summary: summary.json's `metrics` (a comparison, agent or PBD: the metric
/// names and their `value`, and `modelled` where false), or report.json's numbers (a calibration: every number in it, named by
/// its dotted place, e.g. "objective.fitted", "fitted.alpha1"). The parameters come from the case
/// file the folder was written from (named by its .workbench-output stamp): every key, a path
/// resolved to the file it names, and only the keys that differ between rows become columns.
/// Throws workbench::Error "<folder>: <what>" for a folder that is no such output.
SummaryTable summarize(const std::vector<std::filesystem::path>& folders);

/// The table as CSV: `folder`, the parameters, `not_modelled` (the row's not-modelled metrics, separated
/// by spaces), the metrics; a row without a metric leaves its cell empty. Written whole or not at all (workbench::replace_file); an existing `file` is refused
/// unless `overwrite`.
void write_summary_csv(const SummaryTable& table, const std::filesystem::path& file, bool overwrite);
/// The table as JSON: {"parameters": [...], "metrics": [...], "rows": [{"folder", "parameters",
/// "metrics", "not_modelled"}]}, written like the CSV.
void write_summary_json(const SummaryTable& table, const std::filesystem::path& file, bool overwrite);

}  // namespace compare

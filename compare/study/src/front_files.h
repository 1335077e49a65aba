#pragma once
// The front's gate and files (front.cc runs the ladders): front.json, front.csv, the
// work-precision figures and report.html. Private to the compare library.
#include <compare/front.h>
#include <schema/front_options.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace compare::front_files {

/// Rejects (case-file error naming front.gate.<key>.<name>) a gated metric that is not in `metrics`.
void check_gate_names(const schema::FrontGate& gate, const std::vector<std::string>& metrics,
                      const workbench::CaseFile& file);

/// Checks the case's own agent point against [front.gate]: fills out.failures and out.gated.
void apply_gate(const schema::FrontGate& gate, FrontOutcome& out);

/// What front.json and the log say besides the points.
struct FrontHeader {
  std::string title;
  std::vector<std::string> metrics;   ///< every metric judged
  std::vector<std::string> headline;  ///< the log's columns and the case point's verdicts on it
  nlohmann::json reference;           ///< what the reference is (its errors are the outcome's)
};

/// front.json, front.csv, figures/ (compare/front_figures.py) and report.html into `dir`; the
/// verdicts of the case's own point on `log`. A number that is not finite is a workbench::Error
/// naming it, before anything is written.
void write(const std::filesystem::path& dir, const workbench::CaseFile& file, const FrontHeader& header,
           const schema::FrontOptions& options, const FrontOutcome& out, std::ostream& log);

}  // namespace compare::front_files

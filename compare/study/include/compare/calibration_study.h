#pragma once
// The calibration as a workbench study: a calibration case file lists the load cases (each a
// study case file) and what to fit; FEM is solved once per case and reused (docs/calibration.md).
#include <compare/calibration.h>
#include <workbench/case_file.h>

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <vector>

namespace compare {

/// The text of a case file with its [agent] rule set and coefficients set to `k` and a relative
/// mesh file made absolute against `case_dir`: the original's lines, comments and layout are kept,
/// only the values that change are rewritten, shortest-exact (0.3, not 0.29999999999999999), and
/// missing keys are added at the end of [agent] (a new [agent] table at the end if there is none).
/// Given `readings`, [agent] readings is set to them (a one-line array replaced, or added).
std::string with_coefficients(const std::string& text, const std::filesystem::path& case_dir,
                              const agent::Coefficients& k, agent::RuleSet rules,
                              const std::optional<agent::Readings>& readings = std::nullopt);

/// What a calibration file asks for ([calibrate], docs/calibration.md).
struct CalibrationPlan {
  CalibrationOptions options;
  bool cross_validate = true;
  std::vector<std::filesystem::path> case_files;
  std::vector<double> case_weights;
  std::vector<std::filesystem::path> held_out_files;  ///< [[calibrate.held_out]]: scored, never fitted
  std::array<bool, kCoefficientCount> start_given{};  ///< else the start is the first case's own [agent] value
  std::optional<agent::Readings> readings;  ///< calibrate.readings: every case's, else each case's own
};

/// Reads [calibrate] (every coefficient's start and bounds from agent::kCoefficients); throws
/// workbench::Error naming the file and key for anything out of range.
CalibrationPlan read_calibration_plan(const workbench::CaseFile& file);

/// One load case of a calibration from its case file: the agent study (with `readings`, when
/// given, in place of the case's own: `readings_key` is where a mismatch with the loads is
/// reported), every section checked, and the case's FEM reference ([compare.reference]) solved
/// once and sampled onto the agent grid. Progress on `log`.
CalibrationCase load_calibration_case(const workbench::CaseFile& case_file, const agent::Readings* readings,
                                      const workbench::CaseTable* readings_key, std::ostream& log);

/// Reads the calibration file and every case it lists, solves FEM for each, fits, cross-validates,
/// scores the held-out cases with the start and the fit, and writes report.txt, report.json and
/// calibrated/<case>.toml (fitted and held-out cases) into `dir`.
CalibrationResult run_calibration(const workbench::CaseFile& file, const std::filesystem::path& dir, std::ostream& log);

}  // namespace compare

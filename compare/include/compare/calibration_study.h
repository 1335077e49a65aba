#pragma once
// The calibration as a workbench study: a calibration case file lists the load cases (each a
// study case file) and what to fit; FEM is solved once per case and reused (docs/calibration.md).
#include <compare/calibration.h>
#include <workbench/case_file.h>

#include <filesystem>
#include <iosfwd>

namespace compare {

/// Reads the calibration file and every case it lists, solves FEM for each, fits, cross-validates,
/// and writes report.txt, report.json and calibrated/<case>.toml into `dir`.
CalibrationResult run_calibration(const workbench::CaseFile& file, const std::filesystem::path& dir, std::ostream& log);

}  // namespace compare

#pragma once
// One front door per module: a case file in, the study run and its output folder written. The
// command line (cli/*_command.cc) and the Python module (python/workbench_module.cc) both call
// these, so every door checks a case the same way, in the same order:
//   1. every section read and checked, unknown keys refused (schema::check_every_section);
//   2. the module's own reading, then its mesh (nothing is meshed for a case refused anyway);
//   3. the output folder staged (workbench/staged_directory.h), written, moved into place whole.
// (`workbench front` is the comparison's cost-accuracy front: a door of its own, compare/front.h.)
// open_<module>_study is steps 1-2 (what `--check` runs and what Python uses without a folder; fem,
// compare and front read their meshes as they run: check_<module>_study adds them for `--check`);
// run_<module>_study all three. fem, compare and calibrate run distributed under mpirun: every
// rank calls their doors (each step collective, rank 0 owns the folder); agent and pbd run on one
// rank (the command line calls them on rank 0 alone).
//
//   workbench::CaseFile file("cases/seed_plate.toml");
//   const auto run = studies::run_agent_study(file, "out/seed_plate/agent", std::cerr);
//   // run.steps.back(): the full load's state; run.folder: where the files are
#include <agent_study.h>
#include <compare/calibration.h>
#include <compare/compare_study.h>
#include <compare/front.h>
#include <fem_reference/fem.h>
#include <pbd_study.h>
#include <workbench/case_file.h>

#include <filesystem>
#include <iosfwd>
#include <vector>

namespace studies {

/// `workbench agent`: the agent study, checked, mesh imported.
agent_study::AgentStudy open_agent_study(const workbench::CaseFile& file);
struct AgentRun {
  agent_study::AgentStudy study;
  std::vector<agent_study::AgentState> steps;  ///< each load step's state; the last is the full load
  std::filesystem::path folder;                ///< where the files are (the target, moved into place)
};
/// Writes agent_study::write_agent_outputs' files into `folder`.
AgentRun run_agent_study(const workbench::CaseFile& file, const std::filesystem::path& folder, std::ostream& log);

/// `workbench fem`: the FEM problem, checked (collective).
fem_reference::FemProblem open_fem_study(const workbench::CaseFile& file);
/// `workbench fem --check`: open_fem_study and the mesh the run would solve on, checked (collective).
void check_fem_study(const workbench::CaseFile& file);
struct FemRun {
  fem_reference::FemResult result;
  std::filesystem::path folder;  ///< rank 0; empty on the other ranks
};
/// Solves (every rank) and writes the VTU files and fem_reference::write_fem_csv's into `folder`.
FemRun run_fem_study(const workbench::CaseFile& file, const std::filesystem::path& folder, std::ostream& log);

/// `workbench pbd`: the PBD study, checked, mesh read and model built.
pbd_study::PbdStudy open_pbd_study(const workbench::CaseFile& file);
/// Writes pbd_study::write_pbd_outputs' files (with `animate`, the animation too) into `folder`;
/// returns where they are.
std::filesystem::path run_pbd_study(const workbench::CaseFile& file, const std::filesystem::path& folder, bool animate,
                                    std::ostream& log);

/// `workbench compare`: the case checked (collective); the comparison reads the rest as it runs.
void open_compare_study(const workbench::CaseFile& file);
/// `workbench compare --check` (and `workbench front --check`): open_compare_study and what the
/// comparison reads before it runs: the meshes, the same-body check (compare::check_compare);
/// returns the warnings the run would give before it runs.
std::vector<std::string> check_compare_study(const workbench::CaseFile& file);
struct CompareRun {
  compare::CompareOutcome outcome;
  std::filesystem::path folder;  ///< rank 0; empty on the other ranks
};
/// Writes compare::run_compare's files into `folder`.
CompareRun run_compare_study(const workbench::CaseFile& file, const std::filesystem::path& folder, std::ostream& log);

/// `workbench front`: the case checked (the front reads the rest as it runs).
void open_front_study(const workbench::CaseFile& file);
struct FrontRun {
  compare::FrontOutcome outcome;
  std::filesystem::path folder;
};
/// Writes compare::run_front's files into `folder` (one rank: under mpirun with more, an error on every rank).
FrontRun run_front_study(const workbench::CaseFile& file, const std::filesystem::path& folder, std::ostream& log);

/// `workbench calibrate`, on a calibration file (its own format, docs/calibration.md: each case it
/// lists is checked as a study case when it is loaded).
struct CalibrateRun {
  compare::CalibrationResult result;
  std::filesystem::path folder;  ///< rank 0; empty on the other ranks
};
/// Writes compare::run_calibration's files into `folder`.
CalibrateRun run_calibrate_study(const workbench::CaseFile& file, const std::filesystem::path& folder,
                                 std::ostream& log);

}  // namespace studies

#pragma once
// The FEM reference's case glue: a case file -> FemProblem (the plain-data fem.h), and a study's CSV
// files from the FemResult. The solve itself (solve_fem) knows no case file.
//
//   workbench::CaseFile file("cases/seed_plate.toml");
//   auto problem = fem_reference::problem_from_case(file);   // [mesh], [material], [boundary], [[load]], [fem]
//   file.reject_unknown_keys();
//   auto result = fem_reference::solve_fem(problem);
#include <fem_reference/fem.h>
#include <workbench/case_file.h>

#include <array>
#include <filesystem>

namespace fem_reference {

/// Everything the [fem] section of a case holds.
struct FemSection {
  FemOptions options;
  std::array<double, 3> body_force{};   ///< fem.body_force [N/m^3], zero if not given
};

/// Reads [fem] from the case root; range-checks every key.
FemSection read_fem_section(const workbench::CaseTable& root);

/// Reads [mesh], [material], [boundary], [[load]] (workbench::read_study_setup) and [fem]. Does not
/// reject unknown keys: the caller does, once every module has read its sections.
FemProblem problem_from_case(const workbench::CaseFile& file);

/// Writes fem_cells.csv, fem_nodes.csv, fem_reactions.csv and fem_summary.csv into `dir`.
void write_fem_csv(const FemResult& result, const std::filesystem::path& dir);

}  // namespace fem_reference

#pragma once
// Case file -> FEM problem: the glue between workbench::CaseFile and the plain-data fem.h.
//
//   workbench::CaseFile file("cases/seed_plate.toml");
//   auto problem = fem_reference::problem_from_case(file);   // [mesh], [material], [boundary], [[load]], [fem]
//   file.reject_unknown_keys();
//   auto result = fem_reference::solve_fem(problem);
#include <fem_reference/fem.h>
#include <workbench/case_file.h>

#include <array>

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

}  // namespace fem_reference

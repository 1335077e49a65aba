#pragma once
// The PBD angle bending rod against the FEM strip ([compare] model = "pbd", docs/compare.md).
#include <compare/compare_study.h>

namespace compare {

/// The PBD comparison (model = "pbd"); run_compare calls it after reading `options`.
CompareOutcome run_pbd_compare(const workbench::CaseFile& file, const CompareOptions& options,
                               const std::filesystem::path& dir, std::ostream& log);

/// What run_pbd_compare reads and checks before it runs (the rod, the strip's mesh), without running.
void check_pbd_compare(const workbench::CaseFile& file, const CompareOptions& options);

}  // namespace compare

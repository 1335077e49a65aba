#pragma once
// `workbench front`: is the fast model worth running? The agent model at a ladder of agent sizes
// (a PBD case: the PBD rod at a ladder of substeps x iterations) and the FEM at a ladder of mesh
// sizes and degrees, each timed (a warm-up, then the minimum and
// median of N runs from the imported mesh to all of its fields) and scored against the converged
// reference of `workbench compare` on the case's own agent grid; then per field which point is
// dominated and how much cheaper the agents are than the FEM of equal error (docs/front.md).
//
//   workbench::CaseFile file("cases/seed_plate_directional.toml");
//   auto front = compare::run_front(file, "out/front", std::cerr);   // front.json, front.csv, figures/
//   for (const auto& v : front.verdicts) ...                          // v.speedup at equal error
#include <compare/front_verdicts.h>

#include <workbench/case_file.h>

#include <filesystem>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace compare {

struct FrontOutcome {
  std::vector<FrontPoint> points;
  std::string case_point;  ///< the label of the case's own point (agents: its size and rule set; PBD: its steps)
  std::vector<FrontVerdict> verdicts;
  std::vector<FrontCrossover> crossovers;
  /// The reference's own error per metric (its estimate level against it): the floor of the verdicts.
  std::map<std::string, double> reference_errors;
  std::vector<std::string> skipped;   ///< ladder points left out, one line each (which and why)
  std::vector<std::string> failures;  ///< [front.gate] checks that failed, one line each
  std::size_t gated = 0;              ///< checks [front.gate] asks for
};

/// The metrics the front scores and judges: the relative L2 error of every field compared in `dim`
/// dimensions, in the body and in the far field ("far.sigma_y.rel_l2").
std::vector<std::string> front_metrics(int dim);

/// What `workbench front --check` checks: everything run_front reads before it solves (an agent
/// case as `workbench compare --check`; a PBD case's strip, load, stiffness and cells parameter).
/// Returns the warnings the run would give; a workbench::Error when something is wrong.
std::vector<std::string> check_front(const workbench::CaseFile& file);

/// Throws (on every rank, fem_reference::CollectiveError) when more than one MPI rank runs: the
/// front times each model on one core.
void require_one_rank(const workbench::CaseFile& file);

/// Runs the front of the case `file` ([front], docs/case-file.md) and writes front.json, front.csv,
/// fem/ (the reference), figures/ (one work-precision figure per far-field metric) and report.html
/// into `dir`. One rank (under mpirun with more, a workbench::Error). The fast model is the case's
/// compare.model: "agent", or "pbd" (the rod against the FEM strip, docs/front.md "A PBD case").
FrontOutcome run_front(const workbench::CaseFile& file, const std::filesystem::path& dir, std::ostream& log);

}  // namespace compare

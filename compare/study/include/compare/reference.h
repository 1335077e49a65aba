#pragma once
// The FEM reference of a comparison: the same geometry refined and/or of higher degree, solved
// with its output files, with its own discretisation error estimated from a second refinement
// level, and sampled onto the agent grid (compare/sampling.h; docs/compare.md).
#include <agent_study.h>
#include <compare/sampling.h>
#include <fem_reference/fem.h>
#include <schema/compare_options.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <iosfwd>
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace compare {

// The [compare] section's options, read by the case schema (schema/compare_options.h).
using schema::CompareOptions;
using schema::read_compare_options;
using schema::ReferenceOptions;

/// An agent state in the same layout: its stress record (in 2D sigma_z = 0, plane stress, as the
/// agents' strains; the shears the directional and column rule sets' only, the others' 0, the zero
/// model's), and the von Mises stress of those (the general form).
GridFields agent_on_grid(const agent::Grid& grid, const agent::AgentState& state);

/// The comparison's reference for `study`: [compare.reference] resolved for the mesh's dimension;
/// with [mesh] agent_size (the agents voxelized from mesh.file in the run) and no mesh of its own,
/// on mesh.file itself, the true geometry.
ReferenceOptions reference_options(const CompareOptions& options, const agent_study::AgentStudy& study);

/// `problem` set to the level `options`: its degree and refinement, and with options.mesh (the true
/// geometry) that mesh instead of the agents' and the agent_probe_points as probes (the case's
/// [mesh.parameters] kept when it is the case's own mesh.file, and its mesh.unit always).
fem_reference::FemProblem reference_problem(fem_reference::FemProblem problem, const ReferenceOptions& options,
                                            const agent::Grid& grid);

/// A result of reference_problem(.., options, ..) on the agent grid: fem_at_agents on the true
/// geometry (counting in `outside`), else fem_on_grid.
GridFields reference_on_grid(const ReferenceOptions& options, const agent::ImportedMesh& mesh,
                             const fem_reference::FemResult& fem, const std::string& case_name,
                             std::array<std::size_t, 2>& outside);

/// The reference's own error as the converging default judges it: the relative L2 error of the
/// estimate level against the reference over the body's agents, in the stress component whose
/// body norm is the reference's largest (the same number as that field's body rel_l2
/// reference_error in the summary).
struct OwnError {
  std::string field;  ///< kFields name, e.g. "sigma_y"
  double rel_l2 = 0;
};
OwnError body_own_error(const agent::ImportedMesh& mesh, const GridFields& reference, const GridFields& estimate);

/// The reference at two refinement levels, on the agent grid (solve_reference, then
/// estimate_reference_error).
struct Reference {
  ReferenceOptions options;            ///< the level solved (the converging default's last)
  fem_reference::FemResult fem;        ///< the reference solve (its output is in dir/fem)
  GridFields fields;                   ///< the reference on the agent grid
  GridFields estimate_fields;          ///< the second level, on the agent grid
  std::size_t estimate_dofs = 0;
  ReferenceOptions estimate;
  double seconds = 0, estimate_seconds = 0;
  /// With the true geometry (ReferenceOptions::mesh): FEM on the agents' own staircase mesh at the
  /// reference's degree and refinement, on the agent grid (its error against the reference is the
  /// staircase's own), and how many agent centres / nodes lie outside the true geometry.
  std::optional<GridFields> staircase_fields;
  std::size_t staircase_dofs = 0;
  std::array<std::size_t, 2> outside{0, 0};
  /// The converging default (ReferenceOptions::converges): each level solved with its own error,
  /// and, where the last is above the tolerance, why it was not refined further (`stopped`).
  struct Level {
    int refine = 0;
    std::size_t dofs = 0;
    OwnError error;
    double seconds = 0;  ///< the level and its estimate
  };
  std::vector<Level> levels;
  std::string stopped;
  bool estimated = false;  ///< the estimate level already solved (by the converging default)
  /// The converging default stopped above its tolerance: the warning that says so (else empty).
  std::string limits_judgement() const;
};

/// The reference level: solves `problem` (the case's FEM problem; its degree and refine replaced by
/// `options`, its mesh by options.mesh when given) with VTU/CSV output into dir/fem and samples it
/// onto the agent grid. The result's estimate level is set (options.estimate()), not yet solved.
/// With options.converges (the 3D default) it solves level after level, each with its estimate,
/// from options.refine on until the body_own_error is at most options.tolerance, the next level's
/// memory estimate does not fit or kMaxRefine is reached; the last level's files are in dir/fem.
/// Every rank takes the same decisions (the error is rank 0's, summed over the ranks). An empty
/// `dir`: no files (the calibration's references, compare/calibration_study.h).
Reference solve_reference(const fem_reference::FemProblem& problem, const ReferenceOptions& options,
                          const agent::ImportedMesh& mesh, const std::filesystem::path& dir, std::ostream& log);

/// The reference's own error: solves the estimate level of `r` (unless already solved) without
/// output and samples it onto the agent grid; with the true geometry also solves the case's own
/// (staircase) mesh at the reference's level: `staircase_msh` when given (the agents voxelized in
/// the run, written there), else the case's mesh.file. Apart from solve_reference so that the
/// reference's files can be used (the figures drawn) while it runs.
void estimate_reference_error(Reference& r, fem_reference::FemProblem problem, const agent::ImportedMesh& mesh,
                              std::ostream& log, const std::filesystem::path& staircase_msh = {});

/// summary.json's reference.convergence of a converging default: the tolerance, the field judged,
/// each level and its own error, whether it converged, and if not why it stopped.
nlohmann::json convergence_json(const Reference& r);

/// summary.json's reference level: its description, degree, refine and DoFs, and the converging
/// default's convergence (convergence_json); calibration's report.json has the same per case.
nlohmann::json level_json(const Reference& r);

}  // namespace compare

#pragma once
// Fields of both models on the agent grid, in the same layout, so that any two can be compared:
// sigma_x, sigma_y per agent (grid order) and the displacement per grid node; and the FEM
// reference itself: the same geometry refined and/or of higher degree, with its own
// discretisation error estimated from a second refinement level (docs/compare.md).
#include <agent/mesh_import.h>
#include <fem_reference/fem.h>

#include <filesystem>
#include <iosfwd>
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace agent_study {
struct AgentState;  // agent_study.h; the reference itself needs no study glue
}

namespace compare {

struct GridFields {
  std::vector<double> sigma;  ///< 2 per agent: sigma_x, sigma_y [Pa], grid order
  std::vector<double> u;      ///< dim per grid node [m], Grid::node_index order
};

/// The FEM result on the agent grid, found by point location (not by element order): an agent's
/// stress is the mean of the FEM cells whose centre lies in it, a grid node's displacement is
/// the FEM node at the same point. Works for any FEM mesh of the same body whose cells are no
/// larger than the agents and whose nodes include the agent nodes (the agents' own mesh, refined
/// or not). Throws workbench::Error naming `case_name` when an agent of the body gets no FEM cell
/// or a node of the body no FEM node.
GridFields fem_on_grid(const agent::ImportedMesh& mesh, const fem_reference::FemResult& fem,
                       const std::string& case_name);

/// The points where a FEM on another mesh (the true geometry) is evaluated for the agents, as
/// FemProblem::probe_points: the 2 x 2 (2 x 2 x 2) Gauss points of every agent (grid order, air
/// left out), then every grid node of the body (Grid::node_index order).
std::vector<std::array<double, 3>> agent_probe_points(const agent::Grid& grid);

/// A FEM result solved with agent_probe_points(grid) as its probe points, on the agent grid: an
/// agent's stress is the mean of the FEM stress at its Gauss points inside the FEM mesh (the
/// agent's mean, as fem_on_grid gives on the agents' own mesh), a node's displacement the FEM
/// displacement at it. An agent wholly outside the FEM mesh (in the true body's hole or notch)
/// takes the stress of the FEM element whose centre is nearest, a node outside it the displacement
/// of the nearest FEM node; `outside` gets how many agents ([0]) and nodes ([1]) did.
GridFields fem_at_agents(const agent::Grid& grid, const fem_reference::FemResult& fem, std::array<std::size_t, 2>& outside);

/// An agent state in the same layout.
GridFields agent_on_grid(const agent::Grid& grid, const agent_study::AgentState& state);

/// [compare.reference]: FEM on the agents' geometry (or on `mesh`, the true geometry) with `refine`
/// global refinements of the gmsh mesh and polynomial `degree`. degree 1, refine 0 is FEM Q1 on the
/// agents' own mesh.
struct ReferenceOptions {
  int degree = 2;
  int refine = -1;  ///< -1 (the default): 1 in 2D, 0 in 3D (a refined 3D mesh costs 8 times more)
  /// The true (smooth) geometry the agents' staircase was voxelized from (.geo or .msh with the same
  /// physical groups); empty: the agents' own mesh.
  std::filesystem::path mesh;
  /// These options with the default refinement resolved for a `dim`-dimensional mesh.
  ReferenceOptions resolved(int dim) const { return {degree, refine >= 0 ? refine : dim == 2 ? 1 : 0, mesh}; }
  /// The level beside the reference for its error estimate: one refinement coarser; on the
  /// unrefined mesh Q1 for Q2, and for Q1 itself one refinement finer.
  ReferenceOptions estimate() const {
    if (refine > 0) return {degree, refine - 1, mesh};
    if (degree == 2) return {1, 0, mesh};
    return {1, 1, mesh};
  }
  std::string describe() const;  ///< e.g. "FEM Q2, the agents' mesh refined 1 time"
};

/// `problem` set to the level `options`: its degree and refinement, and with options.mesh (the true
/// geometry) that mesh instead of the agents' and the agent_probe_points as probes.
fem_reference::FemProblem reference_problem(fem_reference::FemProblem problem, const ReferenceOptions& options,
                                            const agent::Grid& grid);

/// A result of reference_problem(.., options, ..) on the agent grid: fem_at_agents on the true
/// geometry (counting in `outside`), else fem_on_grid.
GridFields reference_on_grid(const ReferenceOptions& options, const agent::ImportedMesh& mesh,
                             const fem_reference::FemResult& fem, const std::string& case_name,
                             std::array<std::size_t, 2>& outside);

/// The reference at two refinement levels, on the agent grid (solve_reference, then
/// estimate_reference_error).
struct Reference {
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
};

/// The reference level: solves `problem` (the case's FEM problem; its degree and refine replaced by
/// `options`, its mesh by options.mesh when given) with VTU/CSV output into dir/fem and samples it
/// onto the agent grid. The result's estimate level is set (options.estimate()), not yet solved.
Reference solve_reference(const fem_reference::FemProblem& problem, const ReferenceOptions& options,
                          const agent::ImportedMesh& mesh, const std::filesystem::path& dir, std::ostream& log);

/// The reference's own error: solves the estimate level of `r` without output and samples it onto
/// the agent grid; with the true geometry also solves the case's own (staircase) mesh at the
/// reference's level. Apart from solve_reference so that the reference's files can be used (the
/// figures drawn) while it runs.
void estimate_reference_error(Reference& r, fem_reference::FemProblem problem, const ReferenceOptions& options,
                              const agent::ImportedMesh& mesh, std::ostream& log);

}  // namespace compare

#pragma once
// Fields of both models on the agent grid, in the same layout, so that any two can be compared:
// sigma_x, sigma_y per agent (grid order) and the displacement per grid node; and the FEM
// reference itself: the same geometry refined and/or of higher degree, with its own
// discretisation error estimated from a second refinement level (docs/compare.md).
#include <agent/mesh_import.h>
#include <fem_reference/fem.h>

#include <filesystem>
#include <iosfwd>
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

/// An agent state in the same layout.
GridFields agent_on_grid(const agent::Grid& grid, const agent_study::AgentState& state);

/// [compare.reference]: FEM on the agents' geometry with `refine` global refinements of the gmsh
/// mesh and polynomial `degree`. degree 1, refine 0 is FEM Q1 on the agents' own mesh.
struct ReferenceOptions {
  int degree = 2;
  int refine = -1;  ///< -1 (the default): 1 in 2D, 0 in 3D (a refined 3D mesh costs 8 times more)
  /// These options with the default refinement resolved for a `dim`-dimensional mesh.
  ReferenceOptions resolved(int dim) const { return {degree, refine >= 0 ? refine : dim == 2 ? 1 : 0}; }
  /// The level beside the reference for its error estimate: one refinement coarser; on the agents'
  /// own mesh Q1 for Q2, and for Q1 itself one refinement finer.
  ReferenceOptions estimate() const {
    if (refine > 0) return {degree, refine - 1};
    if (degree == 2) return {1, 0};
    return {1, 1};
  }
  std::string describe() const;  ///< e.g. "FEM Q2, agent mesh refined 1 time(s)"
};

/// The reference at two refinement levels, on the agent grid.
struct Reference {
  fem_reference::FemResult fem;        ///< the reference solve (its output is in dir/fem)
  GridFields fields;                   ///< the reference on the agent grid
  GridFields estimate_fields;          ///< the second level, on the agent grid
  std::size_t estimate_dofs = 0;
  ReferenceOptions estimate;
  double seconds = 0, estimate_seconds = 0;
};

/// Solves `problem` (the case's FEM problem; its degree and refine are replaced by `options`) at
/// the reference level, with VTU/CSV output into dir/fem, and at the estimate level without
/// output; samples both onto the agent grid.
Reference solve_reference(fem_reference::FemProblem problem, const ReferenceOptions& options,
                          const agent::ImportedMesh& mesh, const std::filesystem::path& dir, std::ostream& log);

}  // namespace compare

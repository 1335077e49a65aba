#pragma once
// What a FEM solve gives, as plain data: no deal.II, no case file and no solver. Code that only reads
// results (the comparison's sampling, compare/analysis) includes this header and links the small
// `fem_result` library alone, not the FEM reference; fem.h is the problem and the solve.
#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fem_reference {

struct GroupReaction {
  std::string group;
  std::string kind;              ///< "clamped", "roller" or "displacement"
  std::array<double, 3> force{}; ///< force the support exerts on the body [N]
};

struct FemResult {
  int dim = 2;
  int degree = 1;
  std::string model;             ///< "plane_stress", "plane_strain" or "3d"
  std::string cells;             ///< "quadrilateral", "hexahedron", "triangle" or "tetrahedron"
  int ranks = 1;
  std::size_t n_dofs = 0, n_active_cells = 0;

  /// Mesh nodes (the gmsh nodes of the elements, in gmsh node order): 3 coordinates each, and
  /// dim displacement components each [m].
  std::vector<double> node_points, node_displacement;
  std::size_t node_count() const { return node_points.size() / 3; }
  /// Per element in gmsh element order (getElements of the model dimension), averaged over the
  /// element (over its refined children too) [Pa]: centre (3 each), stresses, von Mises.
  std::vector<double> cell_centres;
  std::vector<double> sigma_x, sigma_y, sigma_z, tau_xy, tau_yz, tau_xz, von_mises;
  std::size_t cell_count() const { return sigma_x.size(); }

  std::vector<GroupReaction> reactions;  ///< one per support, in the order of the supports
  std::array<double, 3> applied{};       ///< total applied force (tractions, points, body) [N]

  std::string solver;                    ///< "direct (Amesos_Klu)", "cg+amg (ML)", "cg+gmg (matrix-free, ...)"
  int iterations = 0;                    ///< CG iterations (0 for the direct solver)
  double residual = 0;                   ///< final ||K u - f|| / ||f||
  /// Only when residual > options.tolerance: max_i |f - K u|_i / (|K| |u| + |f|)_i (at most 1e-12,
  /// else solve_fem throws): the rounding floor of an ill-conditioned system, docs/fem-reference.md.
  std::optional<double> backward_error;
  double l2_error = std::numeric_limits<double>::quiet_NaN();  ///< ||u - u_exact||_L2
  double h1_error = std::numeric_limits<double>::quiet_NaN();  ///< |u - u_exact|_H1 (seminorm)
  double mesh_seconds = 0, setup_seconds = 0, assemble_seconds = 0, solve_seconds = 0, output_seconds = 0;
  /// CPU seconds of this process from the mesh on (set-up, assembly, solve, output): on a shared
  /// machine the fair measure of the work beside the wall times above.
  double cpu_seconds = 0;
  double peak_memory_bytes = 0;          ///< this process's peak resident size after solving

  /// The solution at FemProblem::probe_points, in their order (serial runs; under MPI a point on a
  /// partition boundary may be missed). `found`: the point lies in a cell of the mesh (1e-10 in unit
  /// cell coordinates); otherwise u and sigma are 0.
  struct Probe {
    bool found = false;
    std::array<double, 3> u{};      ///< displacement [m]
    std::array<double, 6> sigma{};  ///< stress xx, yy, zz, xy, yz, xz [Pa]
  };
  std::vector<Probe> probes;

  /// Displacement (3 entries, z = 0 in 2D) at the mesh node nearest to x.
  std::array<double, 3> displacement_at(const std::array<double, 3>& x) const;

  /// FemOptions::coarser_level: the same problem on the mesh one refinement coarser, solved from the
  /// multigrid hierarchy; its fields on the same gmsh elements and nodes (no reactions, VTU or exact
  /// errors).
  std::shared_ptr<const FemResult> coarser;
  /// With `coarser`: ||K P u0 - f|| / ||f|| on this mesh (P u0 the coarser solution embedded in its
  /// space), where this solution's CG started.
  double coarser_start_residual = 0;
};

}  // namespace fem_reference

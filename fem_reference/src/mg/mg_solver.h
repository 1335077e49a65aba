// Matrix-free geometric multigrid for the FEM reference (private header; deal.II types).
// The solver of fem.solver = "mg" (and of "auto" on refined quadrilateral/hexahedral meshes and
// unrefined Q2 ones): CG on the elasticity operator applied cell by cell from shared element
// matrices (double; cell_matrix_operator.h), preconditioned by a V-cycle over the global refinement
// levels (Chebyshev-Jacobi smoothing on the same operator in single precision, step-37 style) with
// the coarse mesh solved directly (direct/direct_solver.h) when cheap (elasticity.h), else by one
// ML AMG cycle (amg/amg.h) in Q1 and by one cycle of a p-multigrid to Q1 on the same mesh in Q2.
// No global
// matrix or sparsity pattern is built: about a third of the memory of CG + ML.
#pragma once

#include "amg/amg.h"

#include <fem_reference/fem.h>

#include <deal.II/base/types.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <functional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace fem_reference {

struct MgSettings {
  double lambda = 0, mu = 0;  ///< Lame coefficients of the bilinear form (lambda* in plane stress)
  double tolerance = 1e-10;   ///< relative to ||rhs||
  int max_iterations = 2000;
  long direct_limit = FemOptions{}.direct_limit;  ///< coarse level: elasticity.h's rules
  int smoother_degree = 4;    ///< Chebyshev degree of pre- and post-smoothing
  ModeFrame mode_frame;       ///< of the rigid body modes of the coarse ML cycle
  /// With a `coarser` vector (two levels, homogeneous constraints): the CG on the finest level also
  /// stops once its residual is this share of the one the coarser solution leaves there (0: only
  /// `tolerance`), so that its algebraic error is that small beside the discretisation error the
  /// two levels estimate.
  double coarser_share = 0;
};

struct MgOutcome {
  int iterations = 0;
  double residual = 0;  ///< ||K u - f|| / ||f|| of the condensed system
  std::string solver;
  std::string coarse_solver;  ///< of level 0: "CHOLMOD", "KLU", "ML AMG cycle" or the p-multigrid
  std::vector<std::size_t> matrices_per_level;  ///< element matrices stored per level (the profile)
  /// With a `coarser` vector: the coarse level's own CG (0 when direct), its residual ||K0 u0 - R f|| /
  /// ||R f|| and DoFs, and ||K P u0 - f|| / ||f|| on the finest level, where the fine CG starts.
  int coarser_iterations = 0;
  double coarser_residual = 0, coarser_start_residual = 0;
  std::size_t coarser_dofs = 0;
};

/// Zero boundary conditions of the multigrid levels: boundary ids and the components they hold.
using MgBoundaries = std::vector<std::pair<std::set<dealii::types::boundary_id>, dealii::ComponentMask>>;

/// Degrees 1 and 2 on quadrilaterals/hexahedra. `dof_handler` must have its DoFs distributed;
/// its level DoFs are distributed here. `constraints` are the (possibly inhomogeneous) Dirichlet
/// constraints `rhs` was condensed with; `solution` gets the homogeneous part (constrained entries
/// zero; distribute the constraints afterwards). `profile(name)` starts the profiled phase `name`
/// (ending the one before; nullptr ends the last). Throws SolverControl::NoConvergence.
///
/// `coarser` (two levels only: the mesh refined once; homogeneous constraints): the same problem on
/// the coarse mesh from this hierarchy, solved first (its load R f restricted from the fine one,
/// which for nested spaces is the coarse mesh's own load vector, and its matrix and coarse solver
/// already built), to `tolerance`; `coarser` gets it embedded in the fine space (the coarse FE
/// function itself), and the fine CG starts from it (nested iteration).
template <int dim>
MgOutcome solve_mg(const dealii::Mapping<dim>& mapping, dealii::DoFHandler<dim>& dof_handler,
                   const dealii::AffineConstraints<double>& constraints, const MgBoundaries& boundaries,
                   const dealii::TrilinosWrappers::MPI::Vector& rhs, dealii::TrilinosWrappers::MPI::Vector& solution,
                   const MgSettings& settings, const std::function<void(const char*)>& profile,
                   dealii::TrilinosWrappers::MPI::Vector* coarser = nullptr);

}  // namespace fem_reference

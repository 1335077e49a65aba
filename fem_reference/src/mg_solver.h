// Matrix-free geometric multigrid for the FEM reference (private header; deal.II types).
// The solver of fem.solver = "mg" (and of "auto" on refined quadrilateral/hexahedral meshes): CG on
// the matrix-free elasticity operator, preconditioned by a V-cycle over the global refinement levels
// (Chebyshev-Jacobi smoothing in single precision, step-37 style) with the coarse mesh solved by KLU
// when direct_is_fast for it, else by one ML AMG cycle.
// No global matrix or sparsity pattern is built: about a third of the memory of CG + ML.
#pragma once

#include <fem_reference/fem.h>

#include <deal.II/base/types.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <array>
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
  long direct_limit = FemOptions{}.direct_limit;  ///< coarse level: KLU when direct_is_fast, else one ML cycle
  int smoother_degree = 4;    ///< Chebyshev degree of pre- and post-smoothing
  std::array<double, 3> mode_centre{};  ///< frame of the rigid body modes (rigid_body_modes)
  double mode_size = 1;
};

struct MgOutcome {
  int iterations = 0;
  double residual = 0;  ///< ||K u - f|| / ||f|| of the condensed system
  std::string solver;
  std::vector<std::size_t> matrices_per_level;  ///< element matrices stored per level (the profile)
};

/// Zero boundary conditions of the multigrid levels: boundary ids and the components they hold.
using MgBoundaries = std::vector<std::pair<std::set<dealii::types::boundary_id>, dealii::ComponentMask>>;

/// Whether a sparse direct factorisation of n DoFs is cheap: its expected work, by nested-dissection
/// estimates n^(3/2) in 2D and n^2 in 3D (separators of n^(1/2) and n^(2/3) DoFs), is at most that of
/// a 2D problem of `direct_limit` DoFs. In 3D that is direct_limit^(3/4) DoFs (1 682 for 20 000):
/// beyond it a 3D factorisation fills in so much that KLU takes tens of seconds where AMG takes a
/// fraction of one (docs/performance.md, the solver sweep).
bool direct_is_fast(double n_dofs, int dim, long direct_limit);

/// Degrees 1 and 2 on quadrilaterals/hexahedra. `dof_handler` must have its DoFs distributed;
/// its level DoFs are distributed here. `constraints` are the (possibly inhomogeneous) Dirichlet
/// constraints `rhs` was condensed with; `solution` gets the homogeneous part (constrained entries
/// zero; distribute the constraints afterwards). `profile(name)` starts the profiled phase `name`
/// (ending the one before; nullptr ends the last). Throws SolverControl::NoConvergence.
template <int dim>
MgOutcome solve_mg(const dealii::Mapping<dim>& mapping, dealii::DoFHandler<dim>& dof_handler,
                   const dealii::AffineConstraints<double>& constraints, const MgBoundaries& boundaries,
                   const dealii::TrilinosWrappers::MPI::Vector& rhs, dealii::TrilinosWrappers::MPI::Vector& solution,
                   const MgSettings& settings, const std::function<void(const char*)>& profile);

/// ML smoothed aggregation for elasticity, shared by CG + ML and the multigrid's coarse ML cycle:
/// `modes` holds the rigid body modes (3 columns in 2D, 6 in 3D, of n_local rows each), filled by
/// set_rigid_body_modes for each owned DoF; ML keeps a pointer to them, so they must outlive `amg`.
void set_rigid_body_modes(int dim, const double* x, unsigned component, std::size_t row, std::size_t n_local,
                          std::vector<double>& modes);
/// The rigid body modes of the DoFs in `owned` (set_rigid_body_modes), for ML: every cell of `cells`
/// for which `dof_indices(cell, dofs)` returns true (its DoFs read; false skips it) contributes its
/// owned DoFs, at their support points taken relative to `centre` and scaled by `size` (well
/// conditioned). For the active mesh and for a multigrid level alike.
template <int dim, typename Cells, typename DofIndices>
std::vector<double> rigid_body_modes(const dealii::Mapping<dim>& mapping, const dealii::FiniteElement<dim>& fe,
                                     const Cells& cells, const DofIndices& dof_indices, const dealii::IndexSet& owned,
                                     const std::array<double, 3>& centre, double size) {
  const std::size_t n_local = owned.n_elements();
  std::vector<double> modes(n_local * (dim == 2 ? 3 : 6), 0.0);
  dealii::Quadrature<dim> support_points(fe.get_unit_support_points());
  dealii::FEValues<dim> fe_values(mapping, fe, support_points, dealii::update_quadrature_points);
  std::vector<dealii::types::global_dof_index> dofs(fe.n_dofs_per_cell());
  for (const auto& cell : cells) {
    if (!dof_indices(cell, dofs)) continue;
    fe_values.reinit(cell);
    for (unsigned i = 0; i < dofs.size(); ++i) {
      if (!owned.is_element(dofs[i])) continue;
      double x[3] = {0, 0, 0};
      for (int a = 0; a < dim; ++a) x[a] = (fe_values.quadrature_point(i)[a] - centre[a]) / size;
      set_rigid_body_modes(dim, x, fe.system_to_component_index(i).first, owned.index_within_set(dofs[i]), n_local,
                           modes);
    }
  }
  return modes;
}

/// JxW-free entry (i, j) of the elastic element matrix: lambda div phi_i div phi_j +
/// mu (grad phi_i + grad phi_i^T) : grad phi_j for vector shape functions of components ci, cj with
/// scalar gradients gi, gj. The one formula of the assembled matrix and the multigrid levels.
template <int dim>
double elastic_entry(const dealii::Tensor<1, dim>& gi, const dealii::Tensor<1, dim>& gj, unsigned ci, unsigned cj,
                     double lambda, double mu) {
  double v = lambda * gi[ci] * gj[cj] + mu * gi[cj] * gj[ci];
  if (ci == cj) v += mu * (gi * gj);
  return v;
}

void initialize_elasticity_ml(dealii::TrilinosWrappers::PreconditionAMG& amg,
                              const dealii::TrilinosWrappers::SparseMatrix& matrix, int dim, int degree,
                              std::vector<double>& modes);

}  // namespace fem_reference

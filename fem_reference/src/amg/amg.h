#pragma once
// Algebraic multigrid for elasticity (private header; deal.II types): Trilinos ML smoothed
// aggregation given the rigid body modes as its near-null space. The preconditioner of CG + ML
// (fem.solver = "amg") and the multigrid's coarse cycle on large coarse meshes (mg/mg_solver.cc);
// the problem's check that the supports hold every rigid motion uses the same modes.
#include <deal.II/base/index_set.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/types.h>
#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <array>
#include <cstddef>
#include <vector>

namespace fem_reference {

/// The frame the rigid body modes are evaluated in: centred on the mesh and scaled by its size, so
/// that rotations and translations are of like magnitude (well conditioned).
struct ModeFrame {
  std::array<double, 3> centre{};
  double size = 1;
  /// The frame of a mesh's nodes (3 coordinates each): its bounding box's centre and largest side.
  static ModeFrame of_nodes(const std::vector<double>& nodes, int dim);
  /// A point in the frame (x has 3 entries, 0 beyond dim).
  template <int dim>
  void coordinates(const dealii::Point<dim>& p, double* x) const {
    x[0] = x[1] = x[2] = 0;
    for (int a = 0; a < dim; ++a) x[a] = (p[a] - centre[a]) / size;
  }
};

/// Row `row` of the rigid body modes (3 columns in 2D, 6 in 3D, of n_local rows each, column-major
/// in `modes`) for a DoF of `component` at frame coordinates x: the translations, then the rotations.
void set_rigid_body_modes(int dim, const double* x, unsigned component, std::size_t row, std::size_t n_local,
                          std::vector<double>& modes);

/// The rigid body modes of the DoFs in `owned` (set_rigid_body_modes), for ML: every cell of `cells`
/// for which `dof_indices(cell, dofs)` returns true (its DoFs read; false skips it) contributes its
/// owned DoFs, at their support points in `frame`. For the active mesh and for a multigrid level alike.
template <int dim, typename Cells, typename DofIndices>
std::vector<double> rigid_body_modes(const dealii::Mapping<dim>& mapping, const dealii::FiniteElement<dim>& fe,
                                     const Cells& cells, const DofIndices& dof_indices, const dealii::IndexSet& owned,
                                     const ModeFrame& frame) {
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
      double x[3];
      frame.coordinates(fe_values.quadrature_point(i), x);
      set_rigid_body_modes(dim, x, fe.system_to_component_index(i).first, owned.index_within_set(dofs[i]), n_local,
                           modes);
    }
  }
  return modes;
}

/// ML smoothed aggregation for elasticity, shared by CG + ML and the multigrid's coarse ML cycle:
/// `modes` from rigid_body_modes for the rows of `matrix`; ML keeps a pointer to them, so they must
/// outlive `amg`.
void initialize_elasticity_ml(dealii::TrilinosWrappers::PreconditionAMG& amg,
                              const dealii::TrilinosWrappers::SparseMatrix& matrix, int dim, int degree,
                              std::vector<double>& modes);

}  // namespace fem_reference
